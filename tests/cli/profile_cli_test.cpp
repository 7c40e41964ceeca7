// `--profile NAME` names a declared profile (experiment/profiles.hpp) for
// every command that takes it: an unknown name is exit 2 with "did you
// mean" and the names the files define, and nothing is written; a set of
// files (reproduce) needs the name in one of them and says which files run
// with their own settings, or, for an exclusive profile, are left out.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/process.hpp"
#include "common/temp_dir.hpp"

namespace {
namespace fs = std::filesystem;

const std::string kProfileCnclab = CNCLAB_BINARY_DIR "/cnclab";
const std::string kSource = CNCLAB_SOURCE_DIR;
const std::string kSurface1 = kSource + "/experiments/step_error/surface1.yaml";
const std::string kFriedman = kSource + "/experiments/friedman/friedman1_mlp.yaml";

class ProfileCli : public ::testing::Test {
 protected:
  cnclab::testing::ShellResult cnclab(const std::string& args) const {
    return cnclab::testing::run_shell(dir_.path(), kProfileCnclab + " " + args);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    fs::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  // Files written by the command under test (anything but the test's YAML).
  std::size_t outputs() const {
    std::size_t n = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir_.path())) {
      n += e.is_regular_file() && e.path().extension() != ".yaml";
    }
    return n;
  }
  cnclab::testing::TempDir dir_;
};

void expect_unknown(const cnclab::testing::ShellResult& r, const std::string& fragment) {
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("unknown profile 'quik' (did you mean 'quick'?)"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
}

TEST_F(ProfileCli, RunAndValidateRejectAMisspeltProfileNamingTheDefinedOnes) {
  expect_unknown(cnclab("run " + kSurface1 + " --profile quik --out out --data-dir data"),
                 "profiles defined by " + kSurface1 + " and its includes: quick");
  expect_unknown(cnclab("validate " + kSurface1 + " --profile quik"), "quick");
  EXPECT_EQ(outputs(), 0u);
  // A file without profiles says so.
  const auto none = cnclab("validate " + kFriedman + " --profile quick");
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.err.find(kFriedman + " and its includes define(s) no profiles"), std::string::npos)
      << none.err;
  EXPECT_EQ(cnclab("validate " + kSurface1 + " --profile quick").code, 0);
}

TEST_F(ProfileCli, IncludedProfilesCountAndASweepReachesItsExperiments) {
  // Defined by an include only.
  const fs::path child = write("child.yaml", "include: " + kSurface1 + "\nname: child\n");
  EXPECT_EQ(cnclab("validate " + child.string() + " --profile quick").code, 0);
  expect_unknown(cnclab("validate " + child.string() + " --profile quik"), "quick");
  // A kind: sweep file without profiles of its own: its experiment's count.
  const fs::path sweep =
      write("sweep.yaml", "kind: sweep\nname: s\nexperiment: " + kSurface1 +
                              "\nsweep: {method: grid, parameters: {seed: [1, 2]}}\n");
  EXPECT_EQ(cnclab("validate " + sweep.string() + " --profile quick").code, 0);
  expect_unknown(cnclab("validate " + sweep.string() + " --profile quik"), "quick");
  expect_unknown(cnclab("sweep " + sweep.string() + " --profile quik --out out --data-dir data"),
                 "quick");
  expect_unknown(
      cnclab("sweep " + kSurface1 + " seed=1,2 --profile quik --out out --data-dir data"), "quick");
  // A job of another kind.
  const auto gcode = cnclab("run " + kSource +
                            "/experiments/trochoid/groove_table2.yaml --profile quick --out out");
  EXPECT_EQ(gcode.code, 2) << gcode.err;
  EXPECT_NE(gcode.err.find("unknown profile 'quick'"), std::string::npos) << gcode.err;
  EXPECT_EQ(outputs(), 0u);
}

TEST_F(ProfileCli, TablesCheckTheStudysFiles) {
  fs::create_directories(dir_ / "out");  // --results names an existing folder
  expect_unknown(cnclab("tables step-error --profile quik --results out"),
                 "the experiment files of table step-error");
  expect_unknown(cnclab("tables ik --profile quik --results out"), "quick");
  expect_unknown(cnclab("tables contour-error --profile quik --results out"), "quick");
  expect_unknown(cnclab("tables feedrate --profile quik --results out"), "quick");
  // A declared profile gets as far as the missing results (not a profile error).
  const auto known = cnclab("tables step-error --profile quick --results out");
  EXPECT_NE(known.code, 0);
  EXPECT_EQ(known.err.find("unknown profile"), std::string::npos) << known.err;
  EXPECT_NE(known.err.find("--profile quick"), std::string::npos) << known.err;
}

TEST_F(ProfileCli, ReproduceNeedsTheNameInOneFileAndNamesTheOthers) {
  const std::string small =
      "include: " + kFriedman + "\ntrainer: {epochs: 1}\ndataset: {options: {samples: 120}}\n";
  write("set/a.yaml", small + "name: a\nprofiles: {tiny: {trainer.epochs: 2}}\n");
  write("set/b.yaml", small + "name: b\n");
  const auto typo = cnclab("reproduce set --profile tiyn --out out --data-dir data --quiet");
  EXPECT_EQ(typo.code, 2) << typo.err;
  EXPECT_NE(typo.err.find("unknown profile 'tiyn' (did you mean 'tiny'?); profiles defined by "
                          "the 2 experiment file(s) given: tiny"),
            std::string::npos)
      << typo.err;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  // A file that does not load may be the one that defines it: its own error.
  write("broken/c.yaml", "name: [unclosed\n");
  const auto broken = cnclab("reproduce broken --profile tiny --out out --data-dir data --quiet");
  EXPECT_EQ(broken.code, 2) << broken.err;
  EXPECT_NE(broken.err.find("c.yaml"), std::string::npos) << broken.err;
  EXPECT_EQ(broken.err.find("unknown profile"), std::string::npos) << broken.err;
  const auto ran = cnclab("reproduce set --profile tiny --out out --data-dir data --quiet");
  EXPECT_EQ(ran.code, 0) << ran.out << ran.err;
  EXPECT_NE(ran.err.find("note: profile tiny: not defined by set/b.yaml, which run with their "
                         "own settings"),
            std::string::npos)
      << ran.err;
  // a ran its profile's 2 epochs, b its own 1.
  const auto show = [&](const std::string& name) {
    for (const auto& e : fs::directory_iterator(dir_ / "out/tiny" / name)) {
      if (e.path().extension() == ".h5") return cnclab("show " + e.path().string()).out;
    }
    return std::string();
  };
  EXPECT_NE(show("a").find("after 2 epochs"), std::string::npos) << show("a");
  EXPECT_NE(show("b").find("after 1 epochs"), std::string::npos) << show("b");
}

// The repository's `converged` profile is exclusive: reproduce of every
// experiment with it plans seed 002's three NARX files and nothing else (a
// Slurm dry run: the plan, nothing written or submitted).
TEST_F(ProfileCli, ConvergedReproducesOnlySeed002sNarxStudies) {
  const auto r = cnclab("reproduce " + kSource +
                        "/experiments --profile converged --slurm --dry-run --out out "
                        "--data-dir data");
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.err.find("note: profile converged (exclusive): not run: the "), std::string::npos)
      << r.err;
  const auto summary = r.out.find("== cnclab reproduce --slurm (dry run): 3 experiment(s)");
  ASSERT_NE(summary, std::string::npos) << r.out;
  for (const char* name :
       {"contour_error_narx ", "contour_error_training_methods ", "contour_error_architecture "}) {
    EXPECT_NE(r.out.find(name, summary), std::string::npos) << name << "\n" << r.out;
  }
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

}  // namespace
