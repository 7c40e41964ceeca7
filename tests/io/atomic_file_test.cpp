#include "cnclab/io/atomic_file.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <fstream>
#include <optional>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(AtomicOutput, OnlyThePartialNameExistsBeforeCommitAndOnlyTheFinalAfter) {
  TempDir dir;
  const auto final_path = dir / "sub/r.h5";
  AtomicOutput out(final_path);
  EXPECT_TRUE(fs::is_directory(dir / "sub"));  // parent created
  EXPECT_EQ(out.temp_path().parent_path(), final_path.parent_path());
  std::ofstream(out.temp_path()) << "data";
  EXPECT_EQ(names_in(dir / "sub"), (std::vector<std::string>{out.temp_path().filename()}));
  EXPECT_TRUE(is_partial_path(out.temp_path()));
  EXPECT_FALSE(is_partial_path(final_path));
  out.commit();
  EXPECT_EQ(names_in(dir / "sub"), (std::vector<std::string>{"r.h5"}));
  EXPECT_EQ(slurp(final_path), "data");
}

TEST(AtomicOutput, TemporaryNameFollowsTheDocumentedPattern) {
  TempDir dir;
  AtomicOutput out(dir / "r.h5");
  const std::string name = out.temp_path().filename().string();
  const std::string prefix =
      ".r.h5.partial-" + partial_host_name() + "-" + std::to_string(::getpid()) + "-";
  ASSERT_EQ(name.substr(0, prefix.size()), prefix);
  EXPECT_EQ(name.size(), prefix.size() + 16);
}

TEST(AtomicOutput, CommitReplacesAnExistingFile) {
  TempDir dir;
  const auto final_path = dir / "r.h5";
  std::ofstream(final_path) << "old";
  AtomicOutput out(final_path);
  std::ofstream(out.temp_path()) << "new";
  out.commit();
  EXPECT_EQ(slurp(final_path), "new");
  EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"r.h5"}));
}

TEST(AtomicOutput, AbandonedWriteLeavesPreviousFileIntactAndNoTemporary) {
  TempDir dir;
  const auto final_path = dir / "r.h5";
  std::ofstream(final_path) << "old";
  fs::path temp;
  {
    AtomicOutput out(final_path);
    temp = out.temp_path();
    std::ofstream(temp) << "new but unfinished";
  }
  EXPECT_FALSE(fs::exists(temp));
  EXPECT_EQ(slurp(final_path), "old");
  EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"r.h5"}));
}

TEST(AtomicOutput, DestructorWithoutCommitRemovesTheTemporary) {
  TempDir dir;
  fs::path temp;
  {
    AtomicOutput out(dir / "new.h5");
    temp = out.temp_path();
    std::ofstream(temp) << "x";
    ASSERT_TRUE(fs::exists(temp));
  }
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(AtomicOutput, CommitWithoutAWrittenTemporaryFailsAndKeepsTheOldFile) {
  TempDir dir;
  const auto final_path = dir / "r.h5";
  std::ofstream(final_path) << "old";
  AtomicOutput out(final_path);
  try {
    out.commit();
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(final_path.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(slurp(final_path), "old");
}

TEST(AtomicOutput, TwoWritersGetDistinctTemporaries) {
  TempDir dir;
  AtomicOutput a(dir / "r.h5"), b(dir / "r.h5");
  EXPECT_NE(a.temp_path(), b.temp_path());
}

TEST(AtomicOutput, HostIsTheFirstLabelOfTheHostName) {
  char buffer[256] = {};
  ASSERT_EQ(::gethostname(buffer, sizeof buffer - 1), 0);
  const std::string name(buffer);
  const std::string label = name.substr(0, name.find('.'));
  const bool plain = !label.empty() && std::all_of(label.begin(), label.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-';
  });
  if (!plain) GTEST_SKIP() << "host name '" << name << "' needs sanitising";
  EXPECT_EQ(partial_host_name(), label);
}

TEST(AtomicOutput, PartialNamesRecordTheirWriter) {
  const auto w = partial_writer("r/.x.h5.partial-node-07-4242-0123456789abcdef");
  ASSERT_TRUE(w);
  EXPECT_EQ(w->host, "node-07");
  EXPECT_EQ(w->pid, 4242);
  const auto old = partial_writer(".x.h5.partial-4242-0123456789abcdef");  // before hosts
  ASSERT_TRUE(old);
  EXPECT_EQ(old->host, "");
  EXPECT_EQ(old->pid, 4242);
  TempDir dir;
  AtomicOutput out(dir / "r.h5");
  const auto mine = partial_writer(out.temp_path());
  ASSERT_TRUE(mine);
  EXPECT_EQ(mine->host, partial_host_name());
  EXPECT_EQ(mine->pid, ::getpid());
}

TEST(AtomicOutput, IsPartialPathMatchesOnlyThePattern) {
  EXPECT_TRUE(is_partial_path("results/.x.h5.partial-123-0123456789abcdef"));
  EXPECT_TRUE(is_partial_path("results/.x.h5.partial-host-123-0123456789abcdef"));
  EXPECT_TRUE(is_partial_path("results/.x.h5.partial-a-b_c-123-0123456789abcdef"));
  EXPECT_FALSE(is_partial_path(".x.h5.partial--123-0123456789abcdef"));      // empty host
  EXPECT_FALSE(is_partial_path(".x.h5.partial-a.b-123-0123456789abcdef"));   // dot in host
  EXPECT_FALSE(is_partial_path(".x.h5.partial-host-12a-0123456789abcdef"));  // pid not decimal
  EXPECT_TRUE(is_partial_path(".a.partial-b.partial-1-0123456789abcdef"));
  EXPECT_FALSE(is_partial_path("results/x.h5"));
  EXPECT_FALSE(is_partial_path("results/.x.h5"));
  EXPECT_FALSE(is_partial_path("x.h5.partial-123-0123456789abcdef"));   // no leading dot
  EXPECT_FALSE(is_partial_path(".partial-123-0123456789abcdef"));       // no name
  EXPECT_FALSE(is_partial_path(".x.h5.partial-notes"));                 // no pid-tag
  EXPECT_FALSE(is_partial_path(".x.h5.partial-123-0123456789abcde"));   // 15 hex digits
  EXPECT_FALSE(is_partial_path(".x.h5.partial-12a-0123456789abcdef"));  // pid not decimal
  EXPECT_FALSE(is_partial_path(".x.h5.partial-123-0123456789ABCDEF"));  // upper-case hex
}

// A pid that certainly belongs to no process now: a child that exited and
// was reaped (nullopt in the unlikely case the system reused it already).
std::optional<pid_t> dead_pid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (::kill(pid, 0) == 0 || errno != ESRCH) return std::nullopt;
  return pid;
}

fs::path touch(const fs::path& path) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << "partial";
  return path;
}

std::vector<fs::path> sorted(std::vector<fs::path> v) {
  std::sort(v.begin(), v.end());
  return v;
}

TEST(StalePartials, ALiveWritersFileIsKeptAndADeadWritersIsRemoved) {
  TempDir dir;
  const auto dead = dead_pid();
  if (!dead) GTEST_SKIP() << "the child's pid was reused at once";
  const std::string host = partial_host_name();
  const std::string tag = "-0123456789abcdef";
  const std::string me = std::to_string(::getpid()), gone = std::to_string(*dead);
  const fs::path live = touch(dir / ("results/a/.r.h5.partial-" + host + "-" + me + tag));
  const fs::path stale = touch(dir / ("results/a/b/.r.h5.partial-" + host + "-" + gone + tag));
  const fs::path stale_dataset = touch(dir / ("datasets/.d.h5.partial-" + host + "-" + gone + tag));
  const fs::path elsewhere = touch(dir / ("results/a/.s.h5.partial-elsewhere-" + gone + tag));
  const fs::path older = touch(dir / ("results/.t.h5.partial-" + gone + tag));
  const fs::path result = touch(dir / "results/a/r.h5");

  // results/a lies inside results: each file is seen once.
  const PartialCleanup cleanup = remove_stale_partials(
      {dir / "results", dir / "results/a", dir / "datasets", dir / "missing"}, host);
  EXPECT_EQ(sorted(cleanup.removed), sorted({stale, stale_dataset}));
  EXPECT_EQ(cleanup.removed_pids, std::vector<long long>{*dead});
  EXPECT_EQ(sorted(cleanup.unknown), sorted({elsewhere, older}));
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_FALSE(fs::exists(stale_dataset));
  for (const auto& kept : {live, elsewhere, older, result}) EXPECT_TRUE(fs::exists(kept)) << kept;

  const std::string line = cleanup.summary();
  EXPECT_EQ(line.find("removed 2 partial files of interrupted writes (writer pid " + gone +
                      " no longer running): "),
            0u)
      << line;
  EXPECT_NE(line.find("kept 2 partial files whose writer cannot be checked here"),
            std::string::npos)
      << line;
  EXPECT_EQ(line.find('\n'), std::string::npos) << line;
}

TEST(StalePartials, AKilledWritersTemporaryIsRemovedAndAWritingOnesIsNot) {
  TempDir dir;
  // A writer killed mid-write: its temporary stays behind (no destructor).
  const pid_t child = ::fork();
  if (child == 0) {
    AtomicOutput out(dir / "r.h5");
    std::ofstream(out.temp_path()) << "half";
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  // This process writing the same file right now.
  AtomicOutput writing(dir / "r.h5");
  std::ofstream(writing.temp_path()) << "in progress";
  ASSERT_EQ(names_in(dir.path()).size(), 2u);

  std::ostringstream stream;
  clean_stale_partials({dir.path()}, stream);
  const std::string log = stream.str();
  EXPECT_EQ(names_in(dir.path()),
            std::vector<std::string>{writing.temp_path().filename().string()});
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << log;
  EXPECT_NE(log.find("(writer pid " + std::to_string(child) + " no longer running)"),
            std::string::npos)
      << log;
  writing.commit();
  EXPECT_EQ(slurp(dir / "r.h5"), "in progress");

  // Nothing left to say: no line.
  std::ostringstream quiet;
  clean_stale_partials({dir.path()}, quiet);
  EXPECT_EQ(quiet.str(), "");
}

}  // namespace
}  // namespace cnclab
