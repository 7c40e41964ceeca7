// reproduce's scheduler on a small graph (b needs a; e needs c, which fails
// to load; d alone): upstream results exist before their dependents train,
// a broken upstream skips its dependents, current results are reused, and a
// changed upstream makes its dependents train again.
#include "cnclab/pipeline/reproduce_run.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include "cnclab/experiment/job_kinds.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

const std::string kBase = CNCLAB_SOURCE_DIR "/experiments/friedman/friedman1_mlp.yaml";

void write_graph(const fs::path& dir, int a_epochs) {
  std::ofstream(dir / "a.yaml") << "include: " << kBase
                                << "\nname: a\ntrainer: {epochs: " << a_epochs
                                << "}\ndataset: {options: {samples: 200}}\n";
  std::ofstream(dir / "b.yaml") << "include: " << kBase
                                << "\nname: b\nneeds: [a.yaml]\ntrainer: {epochs: 2}\n"
                                   "dataset: {options: {samples: 200}}\n";
  std::ofstream(dir / "c.yaml") << "include: " << kBase << "\nname: c\nno_such_key: 1\n";
  std::ofstream(dir / "d.yaml") << "include: " << kBase
                                << "\nname: d\ntrainer: {epochs: 2}\n"
                                   "dataset: {options: {samples: 200}}\n";
  std::ofstream(dir / "e.yaml") << "include: " << kBase << "\nname: e\nneeds: [c.yaml]\n";
}

// Each row's action by experiment name (rows of load errors by file stem).
std::map<std::string, ReproduceRow> by_name(const ReproduceRun& run) {
  std::map<std::string, ReproduceRow> rows;
  for (const auto& r : run.rows) rows[fs::path(r.name).stem().string()] = r;
  return rows;
}

TEST(ReproduceRun, UpstreamFirstSkipsBrokenReusesCurrentRerunsChanged) {
  TempDir tmp;
  write_graph(tmp.path(), 2);
  ReproduceInputs inputs;
  for (const char* f : {"a", "b", "c", "d", "e"})
    inputs.files.push_back(tmp / (f + std::string(".yaml")));
  CommandOptions options;
  options.results_dir = tmp / "results";
  options.datasets_dir = tmp / "data";
  options.quiet = true;
  options.jobs = 2;
  std::ostringstream log;

  const ReproduceRun first = run_reproduce(inputs, options, log);
  EXPECT_EQ(first.stopped, 0);
  EXPECT_EQ(first.exit_code, 2);  // c's configuration error
  ASSERT_EQ(first.rows.size(), 5u);
  auto rows = by_name(first);
  EXPECT_EQ(rows["a"].action, "ran");
  EXPECT_EQ(rows["b"].action, "ran");
  EXPECT_EQ(rows["d"].action, "ran");
  EXPECT_EQ(rows["c"].action, "CONFIG ERROR");
  EXPECT_EQ(rows["e"].action, "skipped");
  EXPECT_NE(rows["e"].why.find("upstream"), std::string::npos) << rows["e"].why;
  // b trained after a's result was written (it reads a's result identity).
  ASSERT_FALSE(rows["a"].file.empty());
  ASSERT_FALSE(rows["b"].file.empty());
  EXPECT_LE(fs::last_write_time(rows["a"].file), fs::last_write_time(rows["b"].file));

  const ReproduceRun second = run_reproduce(inputs, options, log);
  rows = by_name(second);
  for (const char* name : {"a", "b", "d"}) EXPECT_EQ(rows[name].action, "reused") << name;

  write_graph(tmp.path(), 3);  // a changes: b must train again, d stays current
  const ReproduceRun third = run_reproduce(inputs, options, log);
  rows = by_name(third);
  EXPECT_EQ(rows["a"].action, "ran");
  EXPECT_EQ(rows["b"].action, "ran");
  EXPECT_EQ(rows["d"].action, "reused");
}

}  // namespace
}  // namespace cnclab
