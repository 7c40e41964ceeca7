#include "cnclab/pipeline/reproduce_command.hpp"

#include <iomanip>

#include "cnclab/pipeline/reproduce_run.hpp"
#include "cnclab/report/tables.hpp"

namespace cnclab {
namespace fs = std::filesystem;

int reproduce_command(const std::vector<std::string>& paths, const CommandOptions& options,
                      std::ostream& out, std::ostream& log) {
  const ReproduceInputs inputs = reproduce_inputs(paths, options.profile);
  if (!inputs.profile_note.empty()) log << "note: " << inputs.profile_note << "\n";
  const ReproduceRun run = run_reproduce(inputs, options, log);
  if (run.stopped != 0) {
    out << "interrupted by signal " << run.stopped
        << ": finished results are kept; run the same command again to resume\n";
    return 128 + run.stopped;
  }
  out << "\n== cnclab reproduce: " << run.rows.size() << " experiment(s) ==\n";
  for (const auto& row : run.rows) {
    out << std::left << std::setw(28) << row.name << " " << std::setw(12) << row.action << " "
        << row.why << "\n";
    if (!row.detail.empty()) out << std::string(30, ' ') << row.detail << "\n";
    if (!row.file.empty()) out << std::string(30, ' ') << row.file << "\n";
  }
  out << run.reports;
  TablesOptions tables;
  tables.results_dir = options.results_dir;
  tables.profile = options.profile;
  tables.check = options.check;
  // The tables of the studies whose files ran here, no note about the others.
  std::vector<fs::path> ran = inputs.files;
  for (const auto& [file, kind] : inputs.jobs) ran.push_back(file);
  const int tables_code = print_available_tables(tables, out, &ran);
  return tables_code == 2 ? 2 : std::max(run.exit_code, tables_code);
}

}  // namespace cnclab
