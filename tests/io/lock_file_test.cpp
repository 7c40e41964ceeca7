// The lock file of io/lock_file.hpp without waiting: try_lock takes a free
// lock and names the holder of a held one, a lock whose holder ended on this
// host is taken over, the file goes with the lock (also when moved), and
// held() tells a live holder from a stale file. Concurrent producers and the
// blocking wait are exercised through the dataset cache
// (tests/data/dataset_cache_test.cpp) and sweeps (tests/cli/sweep_cli_test.cpp).
#include "cnclab/io/lock_file.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <optional>

#include "common/process.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;

std::string this_host() {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  return host;
}

TEST(LockFile, TryLockTakesAFreeLockAndNamesTheHolderOfAHeldOne) {
  testing::TempDir dir;
  const fs::path path = dir / "sub" / ".x.lock";
  std::optional<LockFile> lock = LockFile::try_lock(path);
  ASSERT_TRUE(lock);
  EXPECT_EQ(testing::slurp(path), this_host() + " " + std::to_string(::getpid()) + "\n");
  EXPECT_TRUE(LockFile::held(path));
  // A second taker (another process: this one is alive, so it holds).
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::string holder;
    const bool got = LockFile::try_lock(path, &holder).has_value();
    const bool named = holder == this_host() + " " + std::to_string(::getppid());
    ::_exit(!got && named ? 0 : 1);
  }
  EXPECT_EQ(testing::wait_exit(child), 0) << "a held lock was taken, or its holder not named";
  EXPECT_EQ(LockFile::describe_holder(LockFile::holder(path)),
            "host " + this_host() + ", pid " + std::to_string(::getpid()));
  // Moved, the lock stays; released, the file goes.
  LockFile moved = std::move(*lock);
  lock.reset();
  EXPECT_TRUE(fs::exists(path));
  moved = std::move(*LockFile::try_lock(dir / ".y.lock"));
  EXPECT_FALSE(fs::exists(path));  // the assignment released the first lock
  EXPECT_TRUE(fs::exists(dir / ".y.lock"));
}

TEST(LockFile, ALockWhoseHolderEndedIsTakenOver) {
  testing::TempDir dir;
  const fs::path path = dir / ".x.lock";
  const pid_t gone = ::fork();
  ASSERT_GE(gone, 0);
  if (gone == 0) ::_exit(0);
  testing::wait_exit(gone);
  std::ofstream(path) << this_host() << " " << gone << "\n";
  EXPECT_FALSE(LockFile::held(path));
  const std::optional<LockFile> lock = LockFile::try_lock(path);
  ASSERT_TRUE(lock);
  EXPECT_EQ(testing::slurp(path), this_host() + " " + std::to_string(::getpid()) + "\n");
  // Another host's holder cannot be checked: it holds.
  const fs::path other = dir / ".other.lock";
  std::ofstream(other) << "no-such-host-" << this_host() << " 1\n";
  EXPECT_TRUE(LockFile::held(other));
  std::string holder;
  EXPECT_FALSE(LockFile::try_lock(other, &holder));
  EXPECT_EQ(holder, "no-such-host-" + this_host() + " 1");
}

}  // namespace
}  // namespace cnclab
