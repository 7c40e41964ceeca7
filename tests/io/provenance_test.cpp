#include "cnclab/io/provenance.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <chrono>
#include <ctime>
#include <fstream>
#include <regex>
#include <sstream>

#include "cnclab/core/isa.hpp"
#include "cnclab/io/h5.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;

TEST(Provenance, RoundTripsThroughAGroup) {
  TempDir dir;
  Provenance p = make_provenance(18446744073709551615ull);  // uint64 max survives
  p.derived_seeds = {{"split", 1}, {"init", 18446744073709551614ull}};
  p.end_utc = "2026-01-02T03:04:05Z";
  p.wall_seconds = 12.25;
  p.status = "failed";
  p.failure_reason = "diverged: loss µ NaN";
  {
    H5File f = H5File::create(dir / "p.h5");
    write_provenance(f, "/provenance", p);
    f.close();
  }
  const Provenance r = read_provenance(H5File::open_read(dir / "p.h5"), "/provenance");
  EXPECT_EQ(r.cnclab_version, p.cnclab_version);
  EXPECT_EQ(r.git_commit, p.git_commit);
  EXPECT_EQ(r.master_seed, p.master_seed);
  EXPECT_EQ(r.derived_seeds, p.derived_seeds);
  EXPECT_EQ(r.host, p.host);
  EXPECT_EQ(r.isa, p.isa);
  EXPECT_EQ(r.start_utc, p.start_utc);
  EXPECT_EQ(r.end_utc, p.end_utc);
  EXPECT_EQ(r.wall_seconds, p.wall_seconds);
  EXPECT_EQ(r.libraries, p.libraries);
  EXPECT_EQ(r.status, p.status);
  EXPECT_EQ(r.failure_reason, p.failure_reason);
}

TEST(Provenance, RecordsTheKernelLevelAndReadsFilesWithoutOne) {
  const Provenance p = make_provenance(3);
  EXPECT_EQ(p.isa, to_string(active_isa()));
  EXPECT_FALSE(p.isa.empty());
  // A file written before the level was recorded: every attribute but isa.
  TempDir dir;
  {
    H5File f = H5File::create(dir / "old.h5");
    f.create_group("/provenance");
    for (const char* attr : {"cnclab_version", "git_commit", "host", "start_utc", "end_utc",
                             "status", "failure_reason"}) {
      f.set_attribute("/provenance", attr, "x");
    }
    f.set_attribute("/provenance", "master_seed", "5");
    f.set_attribute("/provenance", "wall_seconds", 1.5);
    f.create_group("/provenance/seeds");
    f.create_group("/provenance/libraries");
    f.close();
  }
  const Provenance r = read_provenance(H5File::open_read(dir / "old.h5"), "/provenance");
  EXPECT_EQ(r.isa, "");
  EXPECT_EQ(r.master_seed, 5u);
  EXPECT_EQ(r.host, "x");
}

TEST(Provenance, VersionMatchesTheProjectVersionInCMakeLists) {
  std::ifstream in(std::string(CNCLAB_SOURCE_DIR) + "/CMakeLists.txt");
  std::stringstream ss;
  ss << in.rdbuf();
  std::smatch m;
  const std::string text = ss.str();
  ASSERT_TRUE(std::regex_search(text, m, std::regex(R"(project\(cnclab VERSION ([0-9.]+))")));
  const Provenance p = make_provenance(7);
  EXPECT_EQ(p.cnclab_version, m[1].str());
  EXPECT_TRUE(std::regex_match(p.git_commit, std::regex("[0-9a-f]{12}(-dirty)?|unknown")))
      << p.git_commit;
  EXPECT_EQ(p.master_seed, 7u);
  EXPECT_FALSE(p.host.empty());
}

TEST(Provenance, UtcTimeIsIso8601AndNow) {
  const std::string s = utc_now_iso8601();
  ASSERT_TRUE(std::regex_match(s, std::regex(R"(\d{4}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}Z)"))) << s;
  std::tm tm{};
  ASSERT_NE(strptime(s.c_str(), "%Y-%m-%dT%H:%M:%SZ", &tm), nullptr);
  const std::time_t parsed = timegm(&tm);
  const std::time_t now = std::time(nullptr);
  EXPECT_LE(std::abs(static_cast<long>(now - parsed)), 2L);
}

TEST(Provenance, LibraryVersionsAreTheCompiledOnes) {
  const auto libs = library_versions();
  EXPECT_EQ(libs.at("Eigen"), std::to_string(EIGEN_WORLD_VERSION) + "." +
                                  std::to_string(EIGEN_MAJOR_VERSION) + "." +
                                  std::to_string(EIGEN_MINOR_VERSION));
  // The runtime library must be the one whose header we compiled against.
  EXPECT_EQ(libs.at("HDF5"), std::to_string(H5_VERS_MAJOR) + "." + std::to_string(H5_VERS_MINOR) +
                                 "." + std::to_string(H5_VERS_RELEASE));
  const std::regex dotted(R"(\d+\.\d+(\.\d+)?)");
  EXPECT_TRUE(std::regex_match(libs.at("yaml-cpp"), dotted)) << libs.at("yaml-cpp");
  EXPECT_TRUE(std::regex_match(libs.at("CLI11"), dotted)) << libs.at("CLI11");
}

TEST(Provenance, HowARunWasMadeRoundTrips) {
  TempDir dir;
  Provenance p = make_provenance(1);
  p.overrides = {"trainer.epochs=3", "model.hidden=[4, 2]"};
  p.profile = "quick";
  p.project_dir = "/home/me/project";
  p.project_commit = std::string(40, 'a');
  p.project_dirty = "yes";
  p.cpu_seconds = 2.5;
  {
    H5File f = H5File::create(dir / "p.h5");
    write_provenance(f, "/provenance", p);
    f.close();
  }
  const Provenance r = read_provenance(H5File::open_read(dir / "p.h5"), "/provenance");
  EXPECT_EQ(r.command_line, p.command_line);
  EXPECT_EQ(r.overrides, p.overrides);
  EXPECT_EQ(r.profile, "quick");
  EXPECT_EQ(r.project_dir, p.project_dir);
  EXPECT_EQ(r.project_commit, p.project_commit);
  EXPECT_EQ(r.project_dirty, "yes");
  EXPECT_EQ(r.cpu_seconds, 2.5);
  // This test binary's argv[0] is the first word of the command line.
  EXPECT_NE(p.command_line.find("io_tests"), std::string::npos) << p.command_line;
}

TEST(Provenance, FilesWrittenBeforeTheRunDetailsStillRead) {
  TempDir dir;
  {
    // The attributes a result had before the command line, overrides,
    // profile, project and CPU time were stored.
    H5File f = H5File::create(dir / "old.h5");
    f.create_group("/provenance");
    for (const char* name : {"cnclab_version", "git_commit", "host", "start_utc", "end_utc",
                             "status", "failure_reason"})
      f.set_attribute("/provenance", name, std::string("x"));
    f.set_attribute("/provenance", "master_seed", std::string("5"));
    f.set_attribute("/provenance", "wall_seconds", 1.0);
    f.create_group("/provenance/seeds");
    f.create_group("/provenance/libraries");
    f.close();
  }
  const Provenance r = read_provenance(H5File::open_read(dir / "old.h5"), "/provenance");
  EXPECT_EQ(r.master_seed, 5u);
  EXPECT_TRUE(r.command_line.empty() && r.overrides.empty() && r.profile.empty());
  EXPECT_TRUE(r.project_commit.empty() && r.project_dirty.empty());
  EXPECT_EQ(r.cpu_seconds, -1);
  // show prints no line for what is unknown.
  for (const auto& [label, text] : provenance_lines(r)) {
    EXPECT_NE(label, "command");
    EXPECT_NE(label, "project");
  }
}

}  // namespace
}  // namespace cnclab
