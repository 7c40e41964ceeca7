// The dataset cache: hit, miss on any change of the generator config,
// --regenerate, and concurrent producers generating a dataset only once
// (an O_EXCL lock file naming its holder).
#include "cnclab/data/dataset_cache.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <iterator>

#include "cnclab/core/config.hpp"
#include "cnclab/data/dataset_spec.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;

DatasetSpec friedman(std::size_t samples) {
  const ConfigDocument doc = ConfigDocument::parse(
      "dataset: {generator: friedman1, options: {samples: " + std::to_string(samples) + "}}\n",
      "t.yaml");
  return read_dataset_spec(doc.root().section("dataset"));
}

std::size_t files_in(const fs::path& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().extension() == ".h5";
  return n;
}

// A generator that ignores its seed (step_error: pure geometry)
// has one cache file whatever the seed; one that uses it (friedman1) has one
// per seed.
TEST(DatasetCache, SeedIsPartOfTheKeyOnlyForGeneratorsThatUseIt) {
  testing::TempDir dir;
  std::ofstream(dir / "s.yaml") << "dataset:\n  generator: step_error\n  options:\n    surface: "
                                << CNCLAB_SOURCE_DIR "/configs/surfaces/surface1.yaml\n"
                                << "    lines: 4\n    points_per_line: 6\n";
  const ConfigDocument doc = ConfigDocument::load(dir / "s.yaml");
  const DatasetSpec step = read_dataset_spec(doc.root().section("dataset"));
  EXPECT_EQ(dataset_cache_file(step, 1, dir.path()), dataset_cache_file(step, 2, dir.path()));
  EXPECT_NE(dataset_cache_file(friedman(10), 1, dir.path()),
            dataset_cache_file(friedman(10), 2, dir.path()));
  // Through the cache itself: the second seed reads the first one's file,
  // and no second file is written.
  const fs::path data = dir / "data";
  const CachedDataset first = obtain_dataset(step, 1, data, nullptr);
  const CachedDataset second = obtain_dataset(step, 2, data, nullptr);
  EXPECT_FALSE(first.reused);
  EXPECT_TRUE(second.reused);
  EXPECT_EQ(second.path, first.path);
  EXPECT_EQ(second.dataset.targets, first.dataset.targets);
  EXPECT_EQ(files_in(data), 1u);
}

TEST(DatasetCache, HitMissAndRegenerate) {
  testing::TempDir dir;
  const CachedDataset first = obtain_dataset(friedman(100), 7, dir.path(), nullptr);
  EXPECT_FALSE(first.reused);
  const CachedDataset again = obtain_dataset(friedman(100), 7, dir.path(), nullptr);
  EXPECT_TRUE(again.reused);
  EXPECT_EQ(again.path, first.path);
  EXPECT_EQ(again.content_hash, first.content_hash);
  EXPECT_EQ(again.dataset.inputs, first.dataset.inputs);
  // Another seed or another option: another file.
  EXPECT_FALSE(obtain_dataset(friedman(100), 8, dir.path(), nullptr).reused);
  EXPECT_FALSE(obtain_dataset(friedman(101), 7, dir.path(), nullptr).reused);
  EXPECT_EQ(files_in(dir.path()), 3u);
  // --regenerate writes a new file with identical content.
  const auto inode_before = fs::last_write_time(first.path);
  const CachedDataset regenerated = obtain_dataset(friedman(100), 7, dir.path(), nullptr, true);
  EXPECT_FALSE(regenerated.reused);
  EXPECT_EQ(regenerated.content_hash, first.content_hash);
  EXPECT_GE(fs::last_write_time(first.path), inode_before);
  EXPECT_TRUE(obtain_dataset(friedman(100), 7, dir.path(), nullptr).reused);
  // A corrupt cached file is regenerated, not used.
  std::ofstream(first.path, std::ios::trunc) << "garbage";
  EXPECT_FALSE(obtain_dataset(friedman(100), 7, dir.path(), nullptr).reused);
}

// <dir>/.<stem>.lock beside a dataset file (built in place: GCC 12 warns
// -Wrestrict, falsely, on "." + std::string here).
fs::path lock_file_of(const fs::path& dataset) {
  std::string name = dataset.stem().string();
  name.insert(0, 1, '.');
  name.append(".lock");
  return dataset.parent_path() / name;
}

TEST(DatasetCache, ConcurrentProducersGenerateOnce) {
  testing::TempDir dir;
  // Big enough that generation takes a while; several processes start
  // together (released by a pipe) and all miss the cache at first.
  constexpr int kProcesses = 4;
  const DatasetSpec spec = friedman(200000);
  int go[2];
  ASSERT_EQ(::pipe(go), 0);
  std::vector<pid_t> pids;
  for (int i = 0; i < kProcesses; ++i) {
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      ::close(go[1]);
      char c;
      while (::read(go[0], &c, 1) < 0) {
      }
      const CachedDataset d = obtain_dataset(spec, 3, dir.path(), nullptr);
      ::_exit(d.reused ? 10 : 20);
    }
    pids.push_back(pid);
  }
  ::close(go[0]);
  ::close(go[1]);  // EOF releases every child at once
  int generated = 0, reused = 0;
  for (pid_t pid : pids) {
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    (WEXITSTATUS(status) == 20 ? generated : reused)++;
  }
  EXPECT_EQ(generated, 1);
  EXPECT_EQ(reused, kProcesses - 1);
  EXPECT_EQ(files_in(dir.path()), 1u);
  EXPECT_TRUE(obtain_dataset(spec, 3, dir.path(), nullptr).reused);
  // The lock file is gone once the dataset is published.
  EXPECT_FALSE(fs::exists(lock_file_of(dataset_cache_file(spec, 3, dir.path()))));
}

std::string this_host() {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  return host;
}

// The lock file names its holder (host and pid; O_EXCL works over NFS where
// flock may not): a live holder is waited for, one that died on this host
// is not.
TEST(DatasetCache, LockFileOfALiveHolderIsWaitedForAndOfADeadOneRemoved) {
  testing::TempDir dir;
  const DatasetSpec spec = friedman(300);
  const fs::path lock = lock_file_of(dataset_cache_file(spec, 5, dir.path()));
  // Held by this (live) process: the child waits until the file goes.
  std::ofstream(lock) << this_host() << " " << ::getpid() << "\n";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) ::_exit(obtain_dataset(spec, 5, dir.path(), nullptr).reused ? 10 : 20);
  ::usleep(400000);
  int status = 0;
  EXPECT_EQ(::waitpid(child, &status, WNOHANG), 0) << "did not wait for the lock's holder";
  EXPECT_EQ(files_in(dir.path()), 0u);
  fs::remove(lock);
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 20);  // it generated

  // Left by a process that has exited (pid reaped): removed, not waited for.
  const pid_t gone = ::fork();
  ASSERT_GE(gone, 0);
  if (gone == 0) ::_exit(0);
  ::waitpid(gone, &status, 0);
  std::ofstream(lock) << this_host() << " " << gone << "\n";
  // --regenerate always takes the lock (a hit would not).
  EXPECT_FALSE(obtain_dataset(spec, 5, dir.path(), nullptr, true).reused);
  EXPECT_FALSE(fs::exists(lock));
}

// /proc/PID/stat's state (the field after the command's ')'), '?' when gone.
char process_state(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  const std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto paren = stat.rfind(')');
  return paren == std::string::npos || paren + 2 >= stat.size() ? '?' : stat[paren + 2];
}

// A holder that has exited but was never reaped (a zombie: kill(pid, 0)
// still succeeds) is dead too: the lock is removed, not waited for forever.
TEST(DatasetCache, LockFileOfAZombieHolderIsRemoved) {
  testing::TempDir dir;
  const DatasetSpec spec = friedman(300);
  const fs::path lock = lock_file_of(dataset_cache_file(spec, 6, dir.path()));
  const pid_t zombie = ::fork();
  ASSERT_GE(zombie, 0);
  if (zombie == 0) ::_exit(0);
  for (int i = 0; i < 200 && process_state(zombie) != 'Z'; ++i) ::usleep(10000);
  ASSERT_EQ(process_state(zombie), 'Z');
  ASSERT_EQ(::kill(zombie, 0), 0);  // what the lock checked before
  std::ofstream(lock) << this_host() << " " << zombie << "\n";

  // The waiter in a child, so that a wait forever fails here instead of hanging.
  const pid_t waiter = ::fork();
  ASSERT_GE(waiter, 0);
  if (waiter == 0) ::_exit(obtain_dataset(spec, 6, dir.path(), nullptr).reused ? 10 : 20);
  int status = 0;
  pid_t ended = 0;
  for (int i = 0; i < 1000 && ended == 0; ++i) {  // up to 10 s
    ended = ::waitpid(waiter, &status, WNOHANG);
    if (ended == 0) ::usleep(10000);
  }
  if (ended == 0) {
    ::kill(waiter, SIGKILL);
    ::waitpid(waiter, &status, 0);
  }
  int zombie_status = 0;
  ::waitpid(zombie, &zombie_status, 0);
  ASSERT_EQ(ended, waiter) << "waited for the zombie holder";
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 20);  // it generated
  EXPECT_FALSE(fs::exists(lock));
}

}  // namespace
}  // namespace cnclab
