// What reproduce runs: the files found under its paths (sorted, once each),
// split into training experiments and `kind:` jobs, the training files a job
// reads added once, and the jobs' prework deduplicated by key.
#include "cnclab/pipeline/reproduce_inputs.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "cnclab/core/error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

void touch(const fs::path& file, const std::string& text = "name: x\n") {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

TEST(FindExperiments, FilesAndFoldersSortedOnceEach) {
  TempDir tmp;
  touch(tmp / "b/z.yaml");
  touch(tmp / "b/a.yml");
  touch(tmp / "b/notes.txt");
  touch(tmp / "b/deeper/c.yaml");
  const std::string dir = (tmp / "b").string();
  const auto files = find_experiments({dir, dir + "/z.yaml"});
  const std::vector<fs::path> expected = {tmp / "b/a.yml", tmp / "b/deeper/c.yaml",
                                          tmp / "b/z.yaml"};
  EXPECT_EQ(files, expected);
  EXPECT_THROW(find_experiments({(tmp / "missing").string()}), ConfigError);
}

// A job that reads a.yaml and b.yaml: given a.yaml, reproduce adds b.yaml
// once (not a.yaml again, nor the job's non-training file).
TEST(ReproduceInputs, JobsUpstreamJoinTheGraphOnce) {
  TempDir tmp;
  touch(tmp / "a.yaml", "name: a\n");
  touch(tmp / "b.yaml", "name: b\n");
  touch(tmp / "g.yaml", "kind: pipeline_test_gcode\n");
  touch(tmp / "job.yaml", "kind: pipeline_test_reader\nname: j\n");
  static bool registered = false;  // the process-wide kind registry takes each kind once
  if (!registered) {
    registered = true;
    JobKind reader;
    reader.kind = "pipeline_test_reader";
    reader.upstream = [](const fs::path& file, const std::string&) {
      const fs::path dir = file.parent_path();
      return std::vector<fs::path>{dir / "a.yaml", dir / "b.yaml", dir / "g.yaml", dir / "b.yaml"};
    };
    register_job_kind(reader);
    JobKind gcode;
    gcode.kind = "pipeline_test_gcode";
    register_job_kind(gcode);
  }
  const ReproduceInputs in =
      reproduce_inputs({(tmp / "a.yaml").string(), (tmp / "job.yaml").string()}, "");
  const std::vector<fs::path> files = {tmp / "a.yaml", tmp / "b.yaml"};
  EXPECT_EQ(in.files, files);
  ASSERT_EQ(in.jobs.size(), 1u);
  EXPECT_EQ(in.jobs[0].first, tmp / "job.yaml");
  EXPECT_EQ(in.jobs[0].second.kind, "pipeline_test_reader");
  EXPECT_TRUE(in.profile_note.empty());
}

// An exclusive profile runs only the files that define it; any other
// profile runs the files without it as written; a misspelt one is an error.
TEST(ReproduceInputs, AnExclusiveProfileRunsOnlyTheFilesDefiningIt) {
  TempDir tmp;
  touch(tmp / "set/a.yaml",
        "name: a\nprofiles:\n  converged: {profile.exclusive: true, x: 1}\n  quick: {x: 2}\n");
  touch(tmp / "set/b.yaml", "name: b\nprofiles:\n  quick: {x: 2}\n");
  touch(tmp / "set/c.yaml", "name: c\n");
  const std::string set = (tmp / "set").string();
  const ReproduceInputs converged = reproduce_inputs({set}, "converged");
  EXPECT_EQ(converged.files, std::vector<fs::path>{tmp / "set/a.yaml"});
  EXPECT_NE(converged.profile_note.find("profile converged (exclusive): not run: the 2 file(s)"),
            std::string::npos)
      << converged.profile_note;
  const ReproduceInputs quick = reproduce_inputs({set}, "quick");
  EXPECT_EQ(quick.files.size(), 3u);
  EXPECT_NE(quick.profile_note.find("c.yaml, which run with their own settings"), std::string::npos)
      << quick.profile_note;
  try {
    reproduce_inputs({set}, "convergd");
    ADD_FAILURE() << "a misspelt profile ran";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'converged'"), std::string::npos)
        << e.what();
  }
}

TEST(JobsPrework, EachKeyOnceInJobOrderAndNoneWithRegenerate) {
  const auto kind_with = [](std::vector<std::string> keys) {
    JobKind k;
    k.kind = "k";
    k.prework = [keys](const fs::path&, const JobContext&) {
      std::vector<JobPrework> out;
      for (const auto& key : keys) out.push_back({key, "dataset " + key, [] {}});
      return out;
    };
    return k;
  };
  JobKind broken;
  broken.prework = [](const fs::path&, const JobContext&) -> std::vector<JobPrework> {
    throw ConfigError("bad file");
  };
  const std::vector<std::pair<fs::path, JobKind>> jobs = {
      {"1.yaml", kind_with({"d1", "d2"})}, {"2.yaml", broken}, {"3.yaml", kind_with({"d2", "d3"})}};
  CommandOptions options;
  std::vector<std::string> keys;
  for (const auto& p : jobs_prework(jobs, options)) keys.push_back(p.key);
  EXPECT_EQ(keys, (std::vector<std::string>{"d1", "d2", "d3"}));
  options.regenerate = true;
  EXPECT_TRUE(jobs_prework(jobs, options).empty());
}

}  // namespace
}  // namespace cnclab
