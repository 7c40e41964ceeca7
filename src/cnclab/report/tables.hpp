#pragma once
// `cnclab tables NAME`: the papers' tables regenerated from result files and
// printed beside the papers' own numbers (results/reference/). Adding a
// table: write its printer in its study's folder and register it from the
// study's register function (src/cli/builtins.cpp).
#include <filesystem>
#include <functional>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/experiment/run_record.hpp"
#include "cnclab/report/text_table.hpp"

namespace cnclab {

struct TablesOptions {
  std::filesystem::path results_dir = "results";  // where `run`/`reproduce` wrote
  // Where a table's inputs are: the experiment YAML files, the transcribed
  // paper numbers and the study manifests (configs/studies). A folder given
  // (--experiments, --reference, --configs) is the only place; "" finds each
  // file as experiments/NAME, results/reference/NAME or configs/NAME in the
  // project (the current directory) or else in cnclab's share folders
  // (core/share_paths.hpp): use experiment_file(), reference_file() and
  // config_file().
  std::filesystem::path experiments_dir;
  std::filesystem::path reference_dir;
  std::filesystem::path configs_dir;
  TableFormat format = TableFormat::text;  // `--format`
  // The profiles: entry the results were made with (`reproduce --quick`:
  // "quick"); experiments load with it to find their result files.
  std::string profile;
  // `--check`: after the tables, each table's declared targets (targets.hpp)
  // against its measurements, PASS/FAIL; exit 1 on any FAIL.
  bool check = false;

  // The input file NAME ("step_error/surface1.yaml", "ik_table5.yaml",
  // "studies/ik_tables.yaml") as described above; MissingResults listing
  // every place looked when a searched name is found nowhere.
  std::filesystem::path experiment_file(const std::filesystem::path& name) const;
  std::filesystem::path reference_file(const std::filesystem::path& name) const;
  std::filesystem::path config_file(const std::filesystem::path& name) const;
};

// A table's measured quantities by name ("tuned.surface1.max_abs_um"), the
// numbers its rows show, for the targets its manifest declares (targets.hpp).
using Measurements = std::map<std::string, double>;

// A table's input results do not exist yet: MissingResults
// (experiment/result_store.hpp), whose message names the command that makes
// them. Tables find their results through a ResultStore{results_dir, profile}.

// A study's tables over one load of its results: print() writes the tables
// (TableEntry::print's output), measure() gives their quantities
// (TableEntry::measure's; empty when the entry has none).
struct LoadedTables {
  std::function<void(std::ostream&)> print;
  std::function<Measurements()> measure;
};

struct TableEntry {
  std::string name;     // `cnclab tables <name>`
  std::string summary;  // one line
  // Prints the table(s); throws MissingResults when results are absent.
  std::function<void(const TablesOptions&, std::ostream&)> print;
  // Optional: the quantities the tables show, by name, computed by the same
  // code as the rows; throws as print does.
  std::function<Measurements(const TablesOptions&)> measure;
  // Optional: the manifest whose `targets:` `--check` checks, relative to
  // TablesOptions::configs_dir ("studies/step_error_tables.yaml").
  std::filesystem::path manifest;
  // Optional: the experiment and job files whose results the tables read, as
  // found through the options (throws as print does when the study's
  // manifest is absent). `--profile NAME` must be defined by one of them
  // (experiment/profiles.hpp), and `reproduce` prints the tables only of the
  // studies whose files it ran.
  std::function<std::vector<std::filesystem::path>(const TablesOptions&)> experiment_files = {};
  // Optional: the folders under RESULTS/figures/ that scripts/figures/ draws
  // for this study ("step_error"); `cnclab report` embeds their PNG files.
  std::vector<std::string> figure_topics = {};
  // Optional: the results read once for both print and measure, for a study
  // whose loading is most of its cost (what `--check`, `reproduce` and
  // `report` call through load_tables). Throws as print does.
  std::function<LoadedTables(const TablesOptions&)> load = {};
};

// entry.load(options), or print and measure with the options, each reading
// the results itself.
LoadedTables load_tables(const TableEntry& entry, const TablesOptions& options);

// Test MSE in the normalised units the network was trained in: the mean of
// (T(prediction) - T(target))^2 with T the run's target scaling.
double normalised_test_mse(const RunRecord& r);
// The same of other test predictions of r (physical units, r.test_targets' shape).
double normalised_test_mse(const RunRecord& r, const Eigen::MatrixXd& predictions);

// The store a table reads its results from: the options' results folder and profile.
ResultStore table_store(const TablesOptions& options);

// A table's footer: the files it read (results, and the reference files its
// paper numbers come from), one line "sources: a, b, ..." in the format's
// comment or list syntax (print_table_notes), paths relative to the working
// directory (source_path_text). Duplicates are listed once, in first-read order.
void print_table_sources(std::ostream& out, TableFormat format,
                         const std::vector<std::filesystem::path>& files);

// Prints `entry`'s tables in `options.format`; for json one document
//   {"name": NAME, "profile": P, "tables": [{"title", "columns", "rows",
//    "notes", "sources"}], "notes": [...]}
// assembled from the record lines the printers write (text_table.hpp): a
// table takes the title before it, and notes and sources that follow it
// (shared by the tables since the last notes); stray text lines become
// document notes.
void print_table_document(const TableEntry& entry, const TablesOptions& options, std::ostream& out);

// Registers a table (src/cli/builtins.cpp, before any command runs);
// std::logic_error for a name registered twice.
void register_table(TableEntry entry);
// The registered tables, in registration order.
const std::vector<TableEntry>& registered_tables();

// Prints table `name`; an empty name lists the tables. Unknown names are
// ConfigErrors listing the known ones, as is a profile that none of the
// table's experiment files defines (TableEntry::experiment_files). With
// options.check, then checks its targets (targets.hpp). Returns the exit
// code: 0, or 1 when a target fails.
int tables_command(const std::string& name, const TablesOptions& options, std::ostream& out);

// Prints every table whose results exist; a table whose inputs are missing
// or unusable gets a one-line note instead (what `cnclab reproduce` ends
// with). `ran` (reproduce: the files it ran) limits both to the tables with
// an experiment file among them: a study the run did not touch (a project's
// starters are not the paper studies) gets neither table nor note. With
// options.check, checks the targets of every table printed and ends with one
// line of totals. Returns the exit code: 0; 1 when a target fails; 2 when a
// manifest's targets are malformed (each said in a note).
int print_available_tables(const TablesOptions& options, std::ostream& out,
                           const std::vector<std::filesystem::path>* ran = nullptr);

}  // namespace cnclab
