#pragma once
// Seed 000's search for Table 2, two ways: the grid over the keep
// probability p (the manifest's `repeats: table2`, every p with its seeds,
// learning rate and momentum at the tuned settings) beside a model-based
// search over p x learning rate x momentum (`repeats: search`, a `kind:
// sweep` file with method tpe and a pruner; model_search.hpp). Each chooses
// its point on the validation MSE (its sweep objective); the chosen point's
// test MSE is reported after the choice, never used to make it.
#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/report/tables.hpp"

namespace cnclab {

// A sweep over Table 2's space and the point it chose.
struct SearchedSpace {
  std::filesystem::path file;  // the kind: sweep file
  std::string method;          // grid, tpe, ...
  std::string space;           // a grid's "key in {0.3, 0.4, ...}" or the model-based
                               // space ("key=uniform(0.3, 1.0), ...")
  std::string pruner;          // model-based: as written in the sweep block
  std::size_t trainings = 0;   // trials with a result (complete, pruned or failed)
  std::size_t complete = 0, pruned = 0;
  std::size_t epochs = 0;                   // trained, summed over those results' histories
  std::string chosen;                       // "key=value ..." of the rank-1 point; "" none
  std::size_t chosen_repeats = 0;           // its complete repeats (the numbers' mean is over them)
  double validation_mse = 0, test_mse = 0;  // the chosen point's means (z-score units)
  std::vector<std::filesystem::path> sources;  // the result files read
  std::vector<std::string> configs;            // their resolved configs
};

// MissingResults naming the command that makes it when the sweep has no
// result (a model-based one: no summary.h5).
SearchedSpace load_searched_space(const std::filesystem::path& file, const TablesOptions& options);

// The manifest's grid (`repeats: table2`) and its search (`repeats: search`).
struct Table2Search {
  SearchedSpace grid, model;
};

struct StepErrorStudy;
// The table (nothing when the manifest names no search).
void print_table2_search(const StepErrorStudy& s, TableFormat format, std::ostream& out);

}  // namespace cnclab
