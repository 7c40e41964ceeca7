// `cnclab reproduce --slurm` without a cluster (fake sbatch/squeue on PATH,
// common/fake_slurm.hpp): the jobs' dependencies are the graph's needs: and
// init_from: as the test's own experiment files declare them, current results
// are reused (no job, no dependency on them), a rerun submits nothing that is
// queued or running, and bad inputs give clear errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "cnclab/sweep/slurm_reproduce_record.hpp"
#include "common/fake_slurm.hpp"
#include "common/process.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::fake_slurm;
using testing::run_shell;
using testing::ShellResult;
using testing::slurp;
using testing::TempDir;
using testing::write_tool;

using testing::kSlurmTestCnclab;
using testing::kSlurmTestExperiment;

using Edges = std::map<std::string, std::set<std::string>>;

// The graph: b needs a; c starts from a (init_from) and needs b; d stands
// alone; s sweeps a (a `kind: sweep` job). The edges the files declare:
const Edges kNeeds = {{"a", {}}, {"b", {"a"}}, {"c", {"a", "b"}}, {"d", {}}};

void write_graph(const fs::path& dir) {
  std::ofstream(dir / "a.yaml") << "include: " << kSlurmTestExperiment
                                << "\nname: a\ntrainer: {epochs: 2}\n"
                                   "dataset: {options: {samples: 200}}\n";
  std::ofstream(dir / "b.yaml") << "include: a.yaml\nname: b\nneeds: [a.yaml]\n";
  std::ofstream(dir / "c.yaml") << "include: a.yaml\nname: c\ninit_from: {experiment: a.yaml}\n"
                                   "needs: [b.yaml]\n";
  std::ofstream(dir / "d.yaml") << "include: a.yaml\nname: d\n";
  std::ofstream(dir / "s.yaml") << "kind: sweep\nname: s\nexperiment: a.yaml\nsweep:\n"
                                   "  parameters: {trainer.learning_rate: [0.001, 0.01]}\n";
}

const std::string kFiles = " a.yaml b.yaml c.yaml d.yaml s.yaml --data-dir data";

// From sbatch calls ("sbatch --parsable [--dependency=TYPE:x:y] ... FILE"),
// each script's dependency type and the jobs it waits for, by script stem
// (cnclab-b) or "sweep"/"final" for a sweep's scripts.
struct Call {
  std::string type;
  std::set<std::string> after;
};
std::map<std::string, Call> sbatch_calls(const std::string& text) {
  std::map<std::string, Call> calls;
  std::istringstream in(text);
  std::string line;
  const std::regex dep(R"(--dependency=(\w+)((?::[^ ,]+)+))");
  const std::regex script(R"(/([\w-]+)\.sbatch\s*$)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (line.find("sbatch --parsable") == std::string::npos) continue;
    if (!std::regex_search(line, m, script)) continue;
    std::string stem = m[1].str();
    if (stem == "merge") stem = "final";
    Call c;
    if (std::regex_search(line, m, dep)) {
      c.type = m[1].str();
      std::istringstream ids(m[2].str().substr(1));
      std::string id;
      while (std::getline(ids, id, ':')) c.after.insert(id);
    }
    calls[stem] = c;
  }
  return calls;
}

TEST(ReproduceSlurm, DryRunDependenciesAreTheGraphsNeeds) {
  TempDir tmp;
  write_graph(tmp.path());
  const ShellResult r = run_shell(
      tmp.path(), kSlurmTestCnclab + " reproduce" + kFiles + " --slurm --dry-run --time 0:10:00");
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const auto calls = sbatch_calls(r.out);
  for (const auto& [name, needs] : kNeeds) {
    ASSERT_TRUE(calls.count("cnclab-" + name)) << name << "\n" << r.out;
    const Call& c = calls.at("cnclab-" + name);
    std::set<std::string> expected;
    for (const auto& up : needs) expected.insert("{" + up + "}");
    EXPECT_EQ(c.after, expected) << name;
    EXPECT_EQ(c.type, needs.empty() ? "" : "afterok") << name;
  }
  // The sweep's array runs after the whole graph (jobs do, as locally).
  ASSERT_TRUE(calls.count("sweep")) << r.out;
  EXPECT_EQ(calls.at("sweep").type, "afterany");
  EXPECT_EQ(calls.at("sweep").after, (std::set<std::string>{"{a}", "{b}", "{c}", "{d}"}));
  EXPECT_NE(r.out.find("#SBATCH --time=0:10:00"), std::string::npos);
  EXPECT_NE(r.out.find("run c.yaml --out results --data-dir data"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("run s.yaml --out results"), std::string::npos) << r.out;  // final job
  EXPECT_FALSE(fs::exists(tmp / "results"));
}

TEST(ReproduceSlurm, ReusesCurrentResultsAndRerunSubmitsNothingInFlight) {
  TempDir tmp;
  write_graph(tmp.path());
  // a is current: no job for it, and b and c do not wait for it.
  ASSERT_EQ(run_shell(tmp.path(), kSlurmTestCnclab + " run a.yaml --data-dir data --quiet").code,
            0);
  const std::string path = fake_slurm(tmp.path());
  const std::string submit = path + kSlurmTestCnclab + " reproduce" + kFiles + " --slurm";
  const ShellResult first = run_shell(tmp.path(), submit);
  ASSERT_EQ(first.code, 0) << first.out << first.err;
  EXPECT_NE(first.out.find("a" + std::string(28, ' ') + "reused"), std::string::npos) << first.out;
  const auto calls = sbatch_calls(slurp(tmp / "calls.txt"));
  EXPECT_FALSE(calls.count("cnclab-a"));
  ASSERT_TRUE(calls.count("cnclab-b") && calls.count("cnclab-c") && calls.count("cnclab-d"));
  EXPECT_TRUE(calls.at("cnclab-b").after.empty());
  EXPECT_TRUE(calls.at("cnclab-d").after.empty());
  const ReproduceRecord record = read_reproduce_record(tmp / "results");
  const auto job_of = [&](const std::string& file) {
    return record.at(reproduce_file_key(tmp / file)).job;
  };
  EXPECT_EQ(calls.at("cnclab-c").after, (std::set<std::string>{job_of("b.yaml")}));
  EXPECT_EQ(calls.at("cnclab-c").type, "afterok");
  EXPECT_EQ(calls.at("sweep").after,
            (std::set<std::string>{job_of("b.yaml"), job_of("c.yaml"), job_of("d.yaml")}));
  const std::string array = record.at(reproduce_file_key(tmp / "s.yaml")).array;
  ASSERT_FALSE(array.empty());
  EXPECT_EQ(calls.at("final").after, (std::set<std::string>{array}));
  EXPECT_EQ(record.size(), 4u);  // b, c, d, s

  // Everything queued: a rerun submits nothing.
  std::ofstream queue(tmp / "queue.txt");
  for (const char* f : {"b.yaml", "c.yaml", "d.yaml", "s.yaml"}) {
    queue << job_of(f) << "|N/A|PENDING\n";
  }
  queue << array << "|0|PENDING\n" << array << "|1|RUNNING\n";
  queue.close();
  const std::size_t before = slurp(tmp / "calls.txt").size();
  const ShellResult second = run_shell(tmp.path(), submit);
  ASSERT_EQ(second.code, 0) << second.out << second.err;
  EXPECT_EQ(slurp(tmp / "calls.txt").size(), before) << slurp(tmp / "calls.txt");
  for (const char* name : {"b", "c", "d", "s"}) {
    EXPECT_NE(second.out.find(std::string(name) + std::string(28, ' ') + "in flight"),
              std::string::npos)
        << name << "\n"
        << second.out;
  }
}

TEST(ReproduceSlurm, BadInputsGiveClearErrors) {
  TempDir tmp;
  write_graph(tmp.path());
  const ShellResult none = run_shell(
      tmp.path(), "PATH=/nonexistent " + kSlurmTestCnclab + " reproduce" + kFiles + " --slurm");
  EXPECT_EQ(none.code, 1);
  EXPECT_NE(none.err.find("sbatch not found on PATH"), std::string::npos) << none.err;
  EXPECT_FALSE(fs::exists(tmp / "results"));

  // sbatch rejects c's job: a and b stay submitted and recorded, nothing after c goes.
  const std::string path = fake_slurm(tmp.path());
  fs::rename(tmp / "bin/sbatch", tmp / "bin/sbatch-accept");
  write_tool(tmp / "bin", "sbatch",
             "case \"$*\" in *cnclab-c.sbatch*) echo 'sbatch: error: Batch job submission "
             "failed: Invalid partition name specified' >&2; exit 1;; esac\nexec '" +
                 (tmp / "bin/sbatch-accept").string() + "' \"$@\"");
  const ShellResult rejected =
      run_shell(tmp.path(), path + kSlurmTestCnclab + " reproduce" + kFiles + " --slurm");
  EXPECT_EQ(rejected.code, 1);
  EXPECT_NE(rejected.err.find("sbatch rejected the job of c (exit 1): sbatch: error: Batch job "
                              "submission failed: Invalid partition name specified"),
            std::string::npos)
      << rejected.err;
  const ReproduceRecord record = read_reproduce_record(tmp / "results");
  EXPECT_EQ(record.size(), 2u);
  EXPECT_TRUE(record.count(reproduce_file_key(tmp / "b.yaml")));
  EXPECT_FALSE(sbatch_calls(slurp(tmp / "calls.txt")).count("cnclab-d"));

  for (const char* bad : {" --slurm --jobs 2", " --partition short", " --slurm --signal TERM@5"}) {
    const ShellResult r =
        run_shell(tmp.path(), path + kSlurmTestCnclab + " reproduce" + kFiles + bad);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.err;
  }
}

}  // namespace
}  // namespace cnclab
