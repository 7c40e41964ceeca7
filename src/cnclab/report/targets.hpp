#pragma once
// Declared targets of a study and their check (`cnclab tables NAME --check`,
// `cnclab reproduce --check`). A table's manifest (TableEntry::manifest,
// under configs/studies/) lists them:
//
//   targets:
//     - name: tuned.surface1.share_abs_below_0.5um  # a quantity the table measures
//       op: ">="                                     # >=, <=, ==, <, >
//       value: 99.5                                  # for results made without --profile
//       profiles: {quick: 5940}                      # optional: values for named profiles
//       source: "seed 000, below Fig. 6: 99.71 %"    # where the target comes from
//
// `value` applies to the full study (results made without a profile). A
// profile's results (`reproduce --quick`) are checked only against the
// targets that give a value for that profile in `profiles:`; the others are
// listed as not checked. Quick results train a few epochs: accuracy targets
// of the paper mean nothing there, structure (sample counts) still does.
// `==` compares exactly: meant for counts.
#include <filesystem>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/report/tables.hpp"

namespace cnclab {

enum class TargetOp { ge, le, eq, lt, gt };

// ">=", "<=", "==", "<", ">".
const char* to_string(TargetOp op);
// `measured op wanted`; false when either is NaN.
bool holds(TargetOp op, double measured, double wanted);

struct Target {
  std::string name;  // a key of the table's Measurements
  TargetOp op = TargetOp::ge;
  double value = 0;                        // the full profile's
  std::map<std::string, double> profiles;  // profile name -> value
  std::string source;  // the paper, section or measurement (docs/) it comes from
  std::string where;   // "<file>:<line>:<col>: targets[i]" for messages

  // The value for results made with `profile` ("" = full); nullopt: not
  // declared for that profile.
  std::optional<double> value_for(const std::string& profile) const;
};

// The `targets:` list of `manifest` (absent key: none). The manifest's other
// keys are left to its own reader. ConfigError naming the file, position and
// key for a malformed entry (unknown key, unknown op, missing source,
// non-finite value); MissingResults when the file does not exist.
std::vector<Target> read_targets(const std::filesystem::path& manifest);

struct TargetResult {
  const Target* target = nullptr;
  std::optional<double> wanted;  // nullopt: not declared for this profile (not checked)
  double measured = 0;
  bool pass = false;
};

// Each target against `measured`. A name that is not measured is a
// ConfigError naming the manifest position, the key and the name, with a
// "did you mean" and the measured names that share its leading part.
std::vector<TargetResult> check_targets(const std::vector<Target>& targets,
                                        const Measurements& measured, const std::string& profile);

// The check of one table as a table of its own (quantity, target, measured,
// PASS/FAIL, source) in `format`, titled with the table and manifest.
void print_target_results(std::ostream& out, TableFormat format, const std::string& table,
                          const std::filesystem::path& manifest, const std::string& profile,
                          const std::vector<TargetResult>& results);

struct TableCheck {
  std::size_t passed = 0, failed = 0, unchecked = 0;
  bool declared = false;  // the table has a manifest with targets
};

// `--check` of one table whose tables were printed (from `loaded`,
// load_tables): reads its manifest's targets, measures, prints the results.
// A table without a manifest or targets prints one line saying so.
// ConfigError as read_targets and check_targets.
TableCheck check_table(const TableEntry& table, const LoadedTables& loaded,
                       const TablesOptions& options, std::ostream& out);

}  // namespace cnclab
