#pragma once
// What a model-based sweep (model_search.hpp) learns beyond its ranking, as
// Optuna reports it: how much each parameter mattered, and with several
// objectives the Pareto front.
//
// In summary.h5 (sweep_summary.hpp):
//   /importance        group, attribute evaluator = "fanova" (Optuna's
//                      FanovaImportanceEvaluator, fixed seed), attribute
//                      target (the objective metric it explains), and
//                      /importance/parameter (strings) with
//                      /importance/value (float64) of the same length,
//                      sorted by value, largest first (fractions summing to 1);
//                      attribute note instead of data when Optuna could not
//                      evaluate it (e.g. fewer than 2 complete trials)
//   /pareto            (several objectives) /pareto/trial: ids of the trials
//                      on the front, attribute objectives ("m1:min, m2:max")
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace cnclab {

class H5File;

struct SearchFindings {
  std::vector<std::string> importance_parameter;  // swept keys, most important first
  std::vector<double> importance_value;           // same length, descending
  std::string importance_target;                  // the objective metric explained
  std::string importance_note;                    // why there is none ("" when there is)
  bool multi_objective = false;
  std::vector<std::string> pareto;  // trial ids on the front (multi_objective)
  std::string objectives;           // "m1:min, m2:max" (multi_objective)
};

void write_search_findings(H5File& file, const SearchFindings& findings);
// nullopt when the file has neither group (grid, random, older summaries).
std::optional<SearchFindings> read_search_findings(const H5File& file);
// For people, below the sweep's ranking.
void print_search_findings(std::ostream& out, const SearchFindings& findings);

}  // namespace cnclab
