#include "cnclab/experiment/tables/tables.hpp"

#include "cnclab/experiment/tables/contour_error_tables.hpp"
#include "cnclab/experiment/tables/ik_tables.hpp"
#include "cnclab/experiment/tables/step_error_tables.hpp"

namespace cnclab {

double normalised_test_mse(const RunRecord& r) {
  const ScalingRecord& y = r.target_scaling;
  return (y.transform(r.test_predictions) - y.transform(r.test_targets)).array().square().mean();
}

std::vector<TableEntry> builtin_tables() {
  return {
      {"ik",
       "seed 004 Table 5 (IK networks per axis, ours vs paper) and the machine-space error of the "
       "predicted joints",
       print_ik_tables},
      {"contour-error",
       "seed 002: NARX training methods, architecture sweep, contour-error estimates and the "
       "contour predictor's accuracy (simulated machine)",
       print_contour_error_tables},
      {"step-error",
       "seed 000 Tables 2-8 (step-error BP network: dropout, surface 1, fine-tuning on surfaces 2 "
       "and 3, timing), ours vs paper, and the normaliser keep/refit comparison",
       print_step_error_tables},
  };
}

int tables_command(const std::string& name, const TablesOptions& options, std::ostream& out) {
  const auto tables = builtin_tables();
  std::string known;
  for (const auto& t : tables) {
    if (t.name == name) {
      t.print(options, out);
      return 0;
    }
    known += (known.empty() ? "" : ", ") + t.name;
  }
  if (name.empty()) {
    for (const auto& t : tables) out << t.name << "  " << t.summary << "\n";
    return 0;
  }
  throw ConfigError("tables: unknown table '" + name + "'; known: " + known);
}

void print_available_tables(const TablesOptions& options, std::ostream& out) {
  for (const auto& t : builtin_tables()) {
    try {
      t.print(options, out);
    } catch (const Error& e) {
      // Missing or failed inputs: the runs' summary above stands; say why
      // the table is absent (`cnclab tables NAME` reports it as an error).
      out << "\n(table " << t.name << " not printed: " << e.what() << ")\n";
    }
  }
}

}  // namespace cnclab
