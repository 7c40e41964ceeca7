// Crash consistency: real `cnclab run` processes killed with SIGKILL at
// seeded random moments (during dataset generation, training and result
// writing). Afterwards every file under the output folders is either a
// complete result/dataset identical in content to an uninterrupted run's, or
// recognisably partial (temporary name) and rejected by the readers and by
// `cnclab show`. Also: a disk-full write (RLIMIT_FSIZE) leaves the previous
// result intact.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/dataset_file.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "common/process.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::slurp;
using testing::TempDir;
using testing::wait_exit;

pid_t spawn(const std::vector<std::string>& args) {
  return testing::spawn_quiet(args);
}

const std::string kCnclab = CNCLAB_BINARY_DIR "/cnclab";
const std::string kExperiment = CNCLAB_SOURCE_DIR "/experiments/friedman/friedman1_mlp.yaml";
// Seed of the kill schedule; override with CNCLAB_KILL_SEED to explore.
constexpr std::uint64_t kKillSeed = 20261124;
constexpr int kKills = 60;

// 10 epochs: kills still land in generation, training and writing, and a run
// takes ~0.1 s of CPU in Release (1/3 of 40 epochs), which matters under ASan.
std::vector<std::string> run_args(const fs::path& out, const fs::path& data) {
  return {kCnclab,   "run",   kExperiment,  "trainer.epochs=10", "dataset.options.samples=3000",
          "--quiet", "--out", out.string(), "--data-dir",        data.string()};
}

std::vector<fs::path> files_under(const fs::path& dir) {
  std::vector<fs::path> out;
  if (!fs::exists(dir)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) out.push_back(e.path());
  }
  return out;
}

struct Tally {
  int complete = 0, partial = 0, torn_but_complete = 0;
};

TEST(CrashConsistency, KilledRunsNeverLeaveAFileThatLooksCompleteButIsNot) {
  TempDir dir;
  // Reference: one uninterrupted run, timed to spread the kills over it.
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(wait_exit(spawn(run_args(dir / "ref", dir / "ref-data"))), 0);
  const double run_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto ref_files = files_under(dir / "ref");
  ASSERT_EQ(ref_files.size(), 1u);
  const RunRecord ref = read_result(ref_files[0]);
  const std::string ref_dataset_hash = ref.dataset_hash;

  const char* seed_env = std::getenv("CNCLAB_KILL_SEED");
  Rng rng(seed_env ? std::strtoull(seed_env, nullptr, 10) : kKillSeed);
  Tally results, datasets;
  for (int k = 0; k < kKills; ++k) {
    // Even kills start with an empty dataset cache (kill during generation
    // and dataset writing possible); odd ones reuse a shared cache.
    const fs::path data = k % 2 == 0 ? dir / ("data-" + std::to_string(k)) : dir / "shared-data";
    const pid_t pid = spawn(run_args(dir / "out", data));
    const double delay = rng.uniform(0.0, 1.05 * run_seconds);
    std::this_thread::sleep_for(std::chrono::duration<double>(delay));
    kill(pid, SIGKILL);
    wait_exit(pid);
  }
  for (const auto& f : files_under(dir / "out")) {
    if (is_partial_path(f)) {
      ++results.partial;
      EXPECT_THROW(read_result(f), IoError) << f;
      continue;
    }
    const RunRecord r = read_result(f);  // throws (fails the test) if torn
    const bool same = r.parameters == ref.parameters &&
                      r.test_predictions == ref.test_predictions && r.metrics == ref.metrics &&
                      r.resolved_yaml == ref.resolved_yaml;
    ++(same ? results.complete : results.torn_but_complete);
  }
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    if (entry.path().filename().string().find("data") == std::string::npos) continue;
    for (const auto& f : files_under(entry.path())) {
      if (f.extension() == ".lock") continue;  // the cache's empty lock files
      if (is_partial_path(f)) {
        ++datasets.partial;
        EXPECT_THROW(read_dataset(f), IoError) << f;
        continue;
      }
      const Dataset d = read_dataset(f);  // verifies the content hash
      ++(d.content_hash() == ref_dataset_hash ? datasets.complete : datasets.torn_but_complete);
    }
  }
  std::printf(
      "kills %d; results: %d complete, %d partial, %d torn-but-complete; datasets: %d "
      "complete, %d partial, %d torn-but-complete\n",
      kKills, results.complete, results.partial, results.torn_but_complete, datasets.complete,
      datasets.partial, datasets.torn_but_complete);
  EXPECT_EQ(results.torn_but_complete, 0);
  EXPECT_EQ(datasets.torn_but_complete, 0);
  // `show` ignores partial files: it refuses them with exit code 1.
  for (const auto& f : files_under(dir / "out")) {
    if (!is_partial_path(f)) continue;
    const std::string cmd = kCnclab + " show '" + f.string() + "' >/dev/null 2>&1";
    EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 1);
    break;
  }
}

TEST(CrashConsistency, DiskFullWriteKeepsThePreviousResult) {
  TempDir dir;
  const auto args = run_args(dir / "out", dir / "data");
  ASSERT_EQ(wait_exit(spawn(args)), 0);
  const auto before = files_under(dir / "out");
  ASSERT_EQ(before.size(), 1u);
  const std::string old_bytes = slurp(before[0]);
  // Same run again with a 16-block file size limit: the result no longer
  // fits. SIGXFSZ is ignored so write() fails with EFBIG instead of killing.
  std::string cmd = "trap '' XFSZ; ulimit -f 16; exec";
  for (const auto& a : args) cmd += " '" + a + "'";
  cmd += " >/dev/null 2>'" + (dir / "err.txt").string() + "'";
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string err = slurp(dir / "err.txt");
  EXPECT_NE(err.find("cnclab: error:"), std::string::npos) << err;
  const auto after = files_under(dir / "out");
  ASSERT_EQ(after.size(), 1u) << "no partial file may remain";
  EXPECT_EQ(slurp(after[0]), old_bytes);
}

}  // namespace
}  // namespace cnclab
