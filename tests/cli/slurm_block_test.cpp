// The `slurm:` block (sweep/slurm_fields.hpp) through the binary: its values
// reach the generated scripts, a flag given on the command line wins (also
// one given with the default's value), a kind: sweep file's block wins over
// its experiment's, an unknown key or a wrong type is exit 2 naming it, and
// the block changes neither the sweep folder (the plan's hash) nor a result's
// identity. No cluster: --dry-run and `reproduce --slurm --dry-run`.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "common/fake_slurm.hpp"
#include "common/process.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::run_shell;
using testing::ShellResult;
using testing::TempDir;

using testing::kSlurmTestCnclab;
using testing::kSlurmTestExperiment;

// 6 small trials of FILE.
std::string block_sweep(const std::string& file, const std::string& dir = " --dir sw") {
  return kSlurmTestCnclab + " sweep " + file +
         " trainer.epochs=2 dataset.options.samples=200 model.hidden=[8] "
         "model.dropout.keep_probability=0.8,0.9,1.0 trainer.learning_rate=1e-3,1e-2 "
         "--data-dir data --out r" +
         dir;
}

// The experiment with the lab's block in configs/slurm/lab.yaml (found as
// configs/... from the experiment's folder upward), and its `slurm:` keys.
void write_experiment(const fs::path& dir, const std::string& own_block = "") {
  fs::create_directories(dir / "configs/slurm");
  std::ofstream(dir / "configs/slurm/lab.yaml")
      << "slurm:\n  partition: lab\n  time: '00:20:00'\n  cpus_per_task: 3\n  mem: 2G\n"
         "  max_concurrent: 4\n  signal: USR2@90\n";
  std::ofstream(dir / "exp.yaml") << "include: [" << kSlurmTestExperiment
                                  << ", configs/slurm/lab.yaml]\n"
                                  << own_block;
}

void expect_lines(const std::string& out, const std::vector<std::string>& lines) {
  for (const auto& line : lines) {
    EXPECT_NE(out.find(line + "\n"), std::string::npos) << line << "\n" << out;
  }
}

TEST(SlurmBlock, BlockValuesReachTheScriptAndGivenFlagsWin) {
  TempDir tmp;
  write_experiment(tmp.path(), "slurm: {mem: 3G}\n");  // the file's own key over the include's
  const ShellResult block = run_shell(tmp.path(), block_sweep("exp.yaml") + " --slurm --dry-run");
  ASSERT_EQ(block.code, 0) << block.err;
  expect_lines(block.out,
               {"#SBATCH --array=0-5%4", "#SBATCH --partition=lab", "#SBATCH --time=00:20:00",
                "#SBATCH --cpus-per-task=3", "#SBATCH --mem=3G", "#SBATCH --signal=B:USR2@90"});

  // Given flags win, --cpus-per-task 1 too although 1 is its default.
  const ShellResult flags =
      run_shell(tmp.path(), block_sweep("exp.yaml") +
                                " --slurm --dry-run --partition short --cpus-per-task 1 "
                                "--max-concurrent 0 --signal USR1@120 --tasks 2");
  ASSERT_EQ(flags.code, 0) << flags.err;
  expect_lines(flags.out,
               {"#SBATCH --array=0-1", "#SBATCH --partition=short", "#SBATCH --cpus-per-task=1",
                "#SBATCH --signal=B:USR1@120", "#SBATCH --time=00:20:00", "#SBATCH --mem=3G"});
  EXPECT_EQ(flags.out.find("--partition=lab"), std::string::npos) << flags.out;

  // Without the block: today's defaults (no partition, time or mem line).
  const ShellResult plain =
      run_shell(tmp.path(), block_sweep(kSlurmTestExperiment, " --dir sw2") + " --slurm --dry-run");
  ASSERT_EQ(plain.code, 0) << plain.err;
  expect_lines(plain.out,
               {"#SBATCH --array=0-5", "#SBATCH --cpus-per-task=1", "#SBATCH --signal=B:USR1@120"});
  for (const char* absent : {"--partition", "--time", "--mem"}) {
    EXPECT_EQ(plain.out.find(std::string("#SBATCH ") + absent), std::string::npos) << absent;
  }
}

TEST(SlurmBlock, SweepFileBlockWinsOverItsExperimentsAndReproduceUsesEachFilesBlock) {
  TempDir tmp;
  write_experiment(tmp.path());
  std::ofstream(tmp / "s.yaml") << "kind: sweep\nname: s\nexperiment: exp.yaml\n"
                                   "overrides: [trainer.epochs=2, dataset.options.samples=200]\n"
                                   "sweep:\n  parameters: {trainer.learning_rate: [0.001, 0.01]}\n"
                                   "slurm: {partition: sweeps, time: '00:05:00'}\n";
  const ShellResult sweep = run_shell(
      tmp.path(), kSlurmTestCnclab + " sweep s.yaml --data-dir data --out r --slurm --dry-run");
  ASSERT_EQ(sweep.code, 0) << sweep.err;
  expect_lines(sweep.out, {"#SBATCH --partition=sweeps", "#SBATCH --time=00:05:00",
                           "#SBATCH --cpus-per-task=3", "#SBATCH --mem=2G"});

  // reproduce --slurm: the experiment's job from its block, the sweep's
  // array from the sweep file's.
  const ShellResult graph =
      run_shell(tmp.path(), kSlurmTestCnclab +
                                " reproduce exp.yaml s.yaml --data-dir data --out r --slurm "
                                "--dry-run --time 00:30:00");
  ASSERT_EQ(graph.code, 0) << graph.out << graph.err;
  expect_lines(graph.out, {"#SBATCH --partition=lab", "#SBATCH --partition=sweeps",
                           "#SBATCH --time=00:30:00"});
  EXPECT_EQ(graph.out.find("--time=00:20:00"), std::string::npos) << graph.out;
  EXPECT_EQ(graph.out.find("--time=00:05:00"), std::string::npos) << graph.out;
}

TEST(SlurmBlock, UnknownKeyOrWrongTypeIsExit2NamingIt) {
  TempDir tmp;
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"slurm: {partitoin: short}\n", "partitoin"},
      {"slurm: {cpus_per_task: many}\n", "slurm.cpus_per_task = many"},
      {"slurm: {cpus_per_task: 0}\n", "slurm.cpus_per_task = 0"},
      {"slurm: {time: '1 day'}\n", "slurm.time = 1 day"},
      {"slurm: {signal: TERM@60}\n", "slurm.signal = TERM@60"}};
  for (const auto& [block, named] : bad) {
    write_experiment(tmp.path(), block);
    const ShellResult r = run_shell(tmp.path(), block_sweep("exp.yaml") + " --slurm --dry-run");
    EXPECT_EQ(r.code, 2) << block << r.out << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << block << r.err;
    EXPECT_NE(r.err.find("exp.yaml"), std::string::npos) << block << r.err;
  }
}

// The block says where trials run, not what they compute: the same sweep
// folder (named by the plan's hash, which covers every trial's resolved
// config) with and without it, and `validate` prints the same resolved
// config.
TEST(SlurmBlock, BlockChangesNeitherTheSweepFolderNorTheResolvedConfig) {
  TempDir tmp;
  write_experiment(tmp.path());
  std::ofstream(tmp / "plain.yaml") << "include: " << kSlurmTestExperiment << "\n";
  const std::regex folder("--dir '?([^' ]*sweep-[0-9a-f]+)");
  std::smatch m;
  std::string folders[2];
  int k = 0;
  for (const char* file : {"exp.yaml", "plain.yaml"}) {
    const ShellResult r = run_shell(tmp.path(), block_sweep(file, "") + " --slurm --dry-run");
    ASSERT_EQ(r.code, 0) << r.err;
    ASSERT_TRUE(std::regex_search(r.out, m, folder)) << r.out;
    folders[k++] = m[1];
  }
  EXPECT_EQ(folders[0], folders[1]);
  const ShellResult a = run_shell(tmp.path(), kSlurmTestCnclab + " validate exp.yaml");
  const ShellResult b = run_shell(tmp.path(), kSlurmTestCnclab + " validate plain.yaml");
  ASSERT_EQ(a.code, 0) << a.err;
  const auto config = [](const std::string& out) { return out.substr(out.find('\n')); };
  EXPECT_EQ(config(a.out), config(b.out));  // after the line naming the file
  EXPECT_EQ(a.out.find("slurm"), std::string::npos) << a.out;
}

}  // namespace
}  // namespace cnclab
