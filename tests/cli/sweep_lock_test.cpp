// One writer per trial of a sweep folder (sweep/sweep_execute.hpp), on real
// processes started together: two identical sweeps, and two shards beside a
// whole sweep, train every trial exactly once between them, all end with
// every trial complete, and every trial keeps its hard link to the result
// store. Who trained what: each process's "[k/n] <id>" progress lines; the
// links: st_nlink and the inode the store's file shares.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "common/process.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::slurp;

const std::string kLockCnclab = CNCLAB_BINARY_DIR "/cnclab";
const std::string kLockExperiment = CNCLAB_SOURCE_DIR "/experiments/friedman/friedman1_mlp.yaml";

// 12 trials (4 keep probabilities x 3 learning rates), each a fraction of a
// second, so that processes started together overlap for the whole sweep.
std::string sweep_command(const std::string& extra) {
  return kLockCnclab + " sweep " + kLockExperiment +
         " trainer.epochs=40 dataset.options.samples=400 model.hidden=[16,8] "
         "model.dropout.keep_probability=0.7,0.8,0.9,1.0 trainer.learning_rate=1e-3,1e-2,1e-1 "
         "--jobs 2 --data-dir data --dir s --out r " +
         extra;
}

// Runs the commands at once (a shell each, in the background), each's
// stdout, stderr and exit code to <name>.out, .err, .code.
void run_together(const fs::path& dir, const std::map<std::string, std::string>& commands) {
  std::string line = "{ ";  // one group: run_shell's `cd DIR &&` applies to all
  for (const auto& [name, command] : commands) {
    line += "(" + command + " >" + name + ".out 2>" + name + ".err; echo $? >" + name + ".code) & ";
  }
  const testing::ShellResult r = testing::run_shell(dir, line + "wait; }");
  ASSERT_EQ(r.code, 0) << r.err;
}

// Trial ids a process trained: its "[k/n] <16 hex> ..." lines.
std::vector<std::string> trained(const std::string& err) {
  static const std::regex line(R"(^\[\d+/\d+\] ([0-9a-f]{16}) )");
  std::vector<std::string> ids;
  std::istringstream in(err);
  for (std::string l; std::getline(in, l);) {
    std::smatch m;
    if (std::regex_search(l, m, line)) ids.push_back(m[1]);
  }
  return ids;
}

// Every trial of s/ trained exactly once by the processes `names`, and
// linked to the result store (r/friedman1_mlp/): two names, one inode.
void expect_each_trial_once_and_linked(const fs::path& dir, const std::vector<std::string>& names) {
  std::map<std::string, int> count;
  for (const auto& n : names) {
    for (const auto& id : trained(slurp(dir / (n + ".err")))) ++count[id];
  }
  std::map<ino_t, fs::path> store;
  for (const auto& e : fs::directory_iterator(dir / "r/friedman1_mlp")) {
    struct stat st {};
    if (e.path().extension() == ".h5" && ::stat(e.path().c_str(), &st) == 0) {
      store[st.st_ino] = e.path();
    }
  }
  std::size_t trials = 0;
  for (const auto& e : fs::directory_iterator(dir / "s/trials")) {
    if (e.path().extension() != ".h5") continue;
    ++trials;
    const std::string id = e.path().stem().string();
    EXPECT_EQ(count[id], 1) << "trial " << id << " trained " << count[id] << " times";
    struct stat st {};
    ASSERT_EQ(::stat(e.path().c_str(), &st), 0);
    EXPECT_EQ(st.st_nlink, 2u) << e.path() << ": its link to the result store is lost";
    EXPECT_TRUE(store.count(st.st_ino)) << e.path() << " is not the store's file";
  }
  EXPECT_EQ(trials, 12u);
  EXPECT_EQ(count.size(), 12u);
  // No lock file is left behind.
  for (const auto& e : fs::directory_iterator(dir / "s/trials")) {
    EXPECT_NE(e.path().extension(), ".lock") << e.path();
  }
}

TEST(SweepLock, TwoIdenticalSweepsStartedTogetherTrainEachTrialOnce) {
  testing::TempDir dir;
  run_together(dir.path(), {{"a", sweep_command("")}, {"b", sweep_command("")}});
  for (const char* n : {"a", "b"}) {
    EXPECT_EQ(slurp(dir / (std::string(n) + ".code")), "0\n")
        << slurp(dir / (std::string(n) + ".err"));
    // Each ends with the whole sweep's summary.
    EXPECT_NE(slurp(dir / (std::string(n) + ".out")).find("12 complete, 0 failed"),
              std::string::npos)
        << slurp(dir / (std::string(n) + ".out"));
  }
  expect_each_trial_once_and_linked(dir.path(), {"a", "b"});
}

// Shards run their own trials; a whole sweep started beside them takes the
// trials no shard holds yet and waits for the others: still once each.
TEST(SweepLock, ShardsAndAWholeSweepShareTheFolderTrialByTrial) {
  testing::TempDir dir;
  run_together(dir.path(), {{"one", sweep_command("--shard 1/2")},
                            {"two", sweep_command("--shard 2/2")},
                            {"all", sweep_command("")}});
  for (const char* n : {"one", "two", "all"}) {
    EXPECT_EQ(slurp(dir / (std::string(n) + ".code")), "0\n")
        << slurp(dir / (std::string(n) + ".err"));
  }
  EXPECT_NE(slurp(dir / "all.out").find("12 complete, 0 failed"), std::string::npos)
      << slurp(dir / "all.out");
  expect_each_trial_once_and_linked(dir.path(), {"one", "two", "all"});
}

// --rerun trains every trial again (the README promises it), each once.
TEST(SweepLock, RerunTrainsEveryTrialAgain) {
  testing::TempDir dir;
  const std::string small = kLockCnclab + " sweep " + kLockExperiment +
                            " trainer.epochs=2 dataset.options.samples=200 model.hidden=[8] "
                            "trainer.learning_rate=1e-3,1e-2 --jobs 2 --data-dir data --dir s ";
  ASSERT_EQ(testing::run_shell(dir.path(), small + "--quiet").code, 0);
  const testing::ShellResult again = testing::run_shell(dir.path(), small);
  EXPECT_NE(again.err.find("2 already done, running 0"), std::string::npos) << again.err;
  const testing::ShellResult rerun = testing::run_shell(dir.path(), small + "--rerun");
  ASSERT_EQ(rerun.code, 0) << rerun.err;
  EXPECT_NE(rerun.err.find("0 already done, running 2"), std::string::npos) << rerun.err;
  EXPECT_EQ(trained(rerun.err).size(), 2u) << rerun.err;
}

}  // namespace
}  // namespace cnclab
