// What a table's notes say its runs ran with (report/run_settings.hpp), and
// the two uses of TableEntry::experiment_files: `tables NAME --profile P`
// needs P defined by one of them, and `reproduce` prints the tables (or
// their "not printed" notes) only of the studies whose files it ran.
#include "cnclab/report/run_settings.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/report/tables.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

TEST(RunSettings, AgreeingValuesOnceDifferingOnesListedOrAsARange) {
  const std::vector<std::string> configs = {
      "trainer:\n  type: sgdm\n  epochs: 5\n  learning_rate: 0.01\nmodel:\n  dropout:\n    "
      "keep_probability: 0.3\n",
      "trainer:\n  type: sgdm\n  epochs: 5\n  learning_rate: 0.01\nmodel:\n  dropout:\n    "
      "keep_probability: 0.9\n",
      "trainer:\n  type: sgdm\n  epochs: 2000\n  learning_rate: 0.01\nmodel:\n  dropout:\n    "
      "keep_probability: 0.5\n",
      "trainer:\n  type: sgdm\n  epochs: 200\n  learning_rate: 0.01\nmodel:\n  dropout:\n    "
      "keep_probability: 0.7\n"};
  EXPECT_EQ(run_settings(configs, {"trainer.type", "trainer.epochs", "trainer.learning_rate",
                                   "trainer.momentum", "model.dropout.keep_probability"}),
            "trainer: type sgdm, epochs 5, 200 or 2000, learning_rate 0.01; model: "
            "dropout.keep_probability 0.3 to 0.9 (4 values)");
  EXPECT_EQ(run_settings({configs[0], configs[2]}, {"trainer.epochs"}),
            "trainer: epochs 5 or 2000");
  // A key only some runs have shows "(absent)"; one no run has is left out.
  EXPECT_EQ(run_settings({configs[0], "trainer: {type: lm}\n"}, {"trainer.type", "trainer.epochs"}),
            "trainer: type sgdm or lm, epochs 5 or (absent)");
  EXPECT_EQ(ran_with("quick", {configs[0]}, {"trainer.epochs"}),
            "ran with profile quick (per the result files' configs): trainer: epochs 5");
  EXPECT_EQ(ran_with("", {configs[0]}, {"trainer.epochs"}),
            "ran with no profile (per the result files' configs): trainer: epochs 5");
}

void write_config(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

// A table reading `file`, whose results are always missing.
void register_missing(const std::string& name, const std::filesystem::path& file) {
  register_table(
      {name,
       "a table for run_settings_test",
       [](const TablesOptions&, std::ostream&) { throw MissingResults("no results"); },
       {},
       {},
       [file](const TablesOptions&) { return std::vector<std::filesystem::path>{file}; }});
}

TEST(TableFiles, ProfileCheckedAgainstTheStudysFilesAndReproduceNotesOnlyItsStudies) {
  testing::TempDir dir;
  write_config(dir / "a.yaml", "name: a\nprofiles: {quick: {trainer.epochs: 1}}\n");
  write_config(dir / "b.yaml", "name: b\n");
  register_missing("files-a", dir / "a.yaml");
  register_missing("files-b", dir / "b.yaml");

  TablesOptions options;
  options.results_dir = dir / "results";
  options.profile = "quik";
  std::ostringstream out;
  try {
    tables_command("files-a", options, out);
    ADD_FAILURE() << "a misspelt profile was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown profile 'quik' (did you mean 'quick'?); "
                                         "profiles defined by the experiment files of table "
                                         "files-a: quick"),
              std::string::npos)
        << e.what();
  }
  options.profile = "quick";
  EXPECT_THROW(tables_command("files-a", options, out), MissingResults);  // past the check
  EXPECT_THROW(tables_command("files-b", options, out), ConfigError);     // b defines none

  const std::vector<std::filesystem::path> ran = {dir / "a.yaml"};
  std::ostringstream some;
  print_available_tables(options, some, &ran);
  EXPECT_NE(some.str().find("table files-a not printed"), std::string::npos) << some.str();
  EXPECT_EQ(some.str().find("table files-b"), std::string::npos) << some.str();
  std::ostringstream all;
  print_available_tables(options, all);
  EXPECT_NE(all.str().find("table files-b not printed"), std::string::npos) << all.str();
}

}  // namespace
}  // namespace cnclab
