// The result store (result_store.hpp): it returns the result of exactly the
// resolved config asked for, never another one however recent, skips files
// that are not complete results, and, when there is none, says which command
// makes it. Checked against results the runner wrote and files altered by
// hand (a second writer: write_result with another status, H5File without
// the `complete` mark).
#include "cnclab/experiment/result_store.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <vector>

#include "cnclab/core/hash.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/runner.hpp"
#include "cnclab/io/file_format.hpp"
#include "cnclab/io/h5.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

const char* kStoreYaml = R"(name: tiny
seed: 5
dataset: {generator: friedman1, options: {samples: 60, inputs: 5, noise_std: 0.5}}
model: {hidden: [4], hidden_activation: tanh}
trainer: {type: sgdm, learning_rate: 0.01, momentum: 0.9, batch_size: 8, epochs: 2}
)";

class Store : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "a.yaml") << kStoreYaml;
    // The same name and seed, another config: the same folder, another file.
    std::ofstream(dir_ / "b.yaml") << "include: a.yaml\ntrainer: {epochs: 3}\n";
  }
  RunOutcome run(const std::string& file) {
    RunOptions o;
    o.results_dir = dir_ / "results";
    o.datasets_dir = dir_ / "datasets";
    return run_experiment(load_experiment(dir_ / file), o);
  }
  std::string message_of(const ResultStore& store, const std::string& file) {
    try {
      store.get(dir_ / file);
    } catch (const MissingResults& e) {
      return e.what();
    }
    ADD_FAILURE() << "no MissingResults for " << file;
    return "";
  }
  TempDir dir_;
};

TEST_F(Store, ReturnsTheResultOfTheResolvedConfig) {
  const RunOutcome a = run("a.yaml");
  ASSERT_TRUE(a.ok);
  const ResultStore store(dir_ / "results");
  const StoredResult r = store.get(dir_ / "a.yaml");
  EXPECT_EQ(r.file, a.result_file);
  // The identity is the hash of the resolved config, the file says so.
  const LoadedExperiment loaded = load_experiment(dir_ / "a.yaml");
  EXPECT_EQ(r.record.config_hash, hash_hex(loaded.resolved_yaml));
  EXPECT_EQ(r.record.resolved_yaml, loaded.resolved_yaml);
  EXPECT_EQ(store.path_of(result_key(loaded)),
            dir_ / "results" / "tiny" /
                ("tiny-seed5-" + hash_hex(loaded.resolved_yaml).substr(0, 8) + ".h5"));
}

TEST_F(Store, NeverPicksAResultOfAnotherConfig) {
  ASSERT_TRUE(run("b.yaml").ok);  // the only (and newest) file in results/tiny/
  const ResultStore store(dir_ / "results");
  const std::string m = message_of(store, "a.yaml");
  EXPECT_NE(m.find("no result for " + (dir_ / "a.yaml").string()), std::string::npos) << m;
  EXPECT_NE(m.find("make it with `cnclab run " + (dir_ / "a.yaml").string() + " --out " +
                   (dir_ / "results").string() + "`"),
            std::string::npos)
      << m;
  // Even under a's name: b's file holds b's config hash.
  const fs::path a_path = store.path_of(result_key(load_experiment(dir_ / "a.yaml")));
  fs::copy_file(store.get(dir_ / "b.yaml").file, a_path);
  const std::string renamed = message_of(store, "a.yaml");
  EXPECT_NE(renamed.find("the result of another config"), std::string::npos) << renamed;
}

TEST_F(Store, SkipsIncompleteFiles) {
  const ResultStore store(dir_ / "results");
  const fs::path path = store.path_of(result_key(load_experiment(dir_ / "a.yaml")));
  fs::create_directories(path.parent_path());
  {
    // A result file without the `complete` mark (a writer that died).
    H5File f = H5File::create(path);
    write_format(f, kResultFormat, kResultFormatVersion);
    f.close();
  }
  const std::string m = message_of(store, "a.yaml");
  EXPECT_NE(m.find("no complete result"), std::string::npos) << m;
  EXPECT_NE(m.find("cnclab run"), std::string::npos) << m;
  EXPECT_THROW(store.existing(result_key(load_experiment(dir_ / "a.yaml"))), IoError);
}

TEST_F(Store, FailedRunsOnlyWhenAccepted) {
  const RunOutcome a = run("a.yaml");
  RunRecord failed = read_result(a.result_file);
  failed.provenance.status = "failed";
  failed.provenance.failure_reason = "diverged at epoch 2";
  write_result(a.result_file, failed);
  const ResultStore store(dir_ / "results");
  try {
    store.get(dir_ / "a.yaml");
    ADD_FAILURE() << "a failed run was returned";
  } catch (const MissingResults&) {
    ADD_FAILURE() << "a failed run is a result, not a missing one";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("diverged at epoch 2"), std::string::npos) << e.what();
  }
  EXPECT_EQ(store.get(dir_ / "a.yaml", Accept::complete_or_failed).record.provenance.status,
            "failed");
}

// get_all reads many results with one isolated child; each file's answer is
// what get() gives for it alone, errors included.
TEST_F(Store, GetAllGivesWhatGetGivesForEachFile) {
  std::ofstream(dir_ / "c.yaml") << "include: a.yaml\nseed: 6\n";
  ASSERT_TRUE(run("a.yaml").ok);
  ASSERT_TRUE(run("c.yaml").ok);
  const ResultStore store(dir_ / "results");
  const std::vector<fs::path> files = {dir_ / "a.yaml", dir_ / "c.yaml", dir_ / "a.yaml"};
  const std::vector<StoredResult> all = store.get_all(files);
  ASSERT_EQ(all.size(), files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    const StoredResult one = store.get(files[i]);
    EXPECT_EQ(all[i].file, one.file);
    EXPECT_EQ(all[i].record.config_hash, one.record.config_hash);
    EXPECT_EQ(all[i].record.test_predictions, one.record.test_predictions);
  }
  EXPECT_NE(all[0].file, all[1].file);
  // c's file without the `complete` mark: get_all throws get()'s MissingResults.
  const fs::path c_path = all[1].file;
  {
    H5File f = H5File::create(c_path);
    write_format(f, kResultFormat, kResultFormatVersion);
    f.close();
  }
  const std::string alone = message_of(store, "c.yaml");
  try {
    store.get_all(files);
    ADD_FAILURE() << "an incomplete result was returned";
  } catch (const MissingResults& e) {
    EXPECT_EQ(std::string(e.what()), alone);
  }
  // No file at all: the same.
  fs::remove(c_path);
  EXPECT_THROW(store.get_all(files), MissingResults);
  EXPECT_EQ(store.get_all({dir_ / "a.yaml"}).front().file, all[0].file);
}

TEST_F(Store, CommandNamesProfileAndFolder) {
  std::ofstream(dir_ / "down.yaml")
      << "include: a.yaml\nname: down\ninit_from: {experiment: a.yaml}\n";
  const LoadedExperiment down = load_experiment(dir_ / "down.yaml");
  // The CLI's default folder for a profile needs no --out.
  EXPECT_EQ(ResultStore("results/quick", "quick").make_command(result_key(down)),
            "cnclab reproduce " + (dir_ / "down.yaml").string() + " --profile quick");
  EXPECT_EQ(ResultStore("results").make_command(result_key(load_experiment(dir_ / "a.yaml"))),
            "cnclab run " + (dir_ / "a.yaml").string());
  EXPECT_EQ(
      ResultStore("elsewhere", "quick").make_command(result_key(down)),
      "cnclab reproduce " + (dir_ / "down.yaml").string() + " --profile quick --out elsewhere");
  // ROOT/P names ROOT (results_folder turns it back into ROOT/P).
  EXPECT_EQ(ResultStore("runs/quick", "quick").make_command(result_key(down)),
            "cnclab reproduce " + (dir_ / "down.yaml").string() + " --profile quick --out runs");
  // A missing experiment file is a missing result too.
  EXPECT_THROW(ResultStore(dir_ / "results").get(dir_ / "nope.yaml"), MissingResults);
}

// The one rule (results_folder): ROOT/P, except for a given ROOT in the old
// layout (results directly in ROOT, no ROOT/P), used as it is with a note.
TEST(ResultsFolder, RootAndProfileWithTheOldLayoutKept) {
  TempDir dir;
  const fs::path root = dir.path() / "r";
  EXPECT_EQ(results_folder(root, "", true).dir, root);
  EXPECT_EQ(results_folder(root, "quick", true).dir, root / "quick");  // nothing there yet
  fs::create_directories(root / "tiny");
  std::ofstream(root / "tiny" / "notes.txt") << "not a result";
  EXPECT_EQ(results_folder(root, "quick", true).dir, root / "quick");  // no results in ROOT
  std::ofstream(root / "tiny" / "tiny-seed5-0123abcd.h5") << "";
  const ResultsFolder old = results_folder(root, "quick", true);
  EXPECT_EQ(old.dir, root);
  EXPECT_NE(old.note.find(root.string() + " holds results directly and has no quick/ folder"),
            std::string::npos)
      << old.note;
  // The default root never falls back (reproduce --quick always wrote results/quick).
  EXPECT_EQ(results_folder(root, "quick", false).dir, root / "quick");
  EXPECT_EQ(results_folder(root, "quick", false).note, "");
  // Once ROOT/P exists, it is the folder.
  fs::create_directories(root / "quick");
  EXPECT_EQ(results_folder(root, "quick", true).dir, root / "quick");
  EXPECT_EQ(results_folder(root, "quick", true).note, "");
  // A sweep folder counts as results too.
  const fs::path sweeps = dir.path() / "s";
  fs::create_directories(sweeps / "narx" / "sweep-1a2b3c4d");
  EXPECT_EQ(results_folder(sweeps, "quick", true).dir, sweeps);
}

}  // namespace
}  // namespace cnclab
