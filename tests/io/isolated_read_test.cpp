#include "cnclab/io/isolated_read.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;
namespace fs = std::filesystem;

// The marker a crash handler writes: a fixed buffer, since a signal handler
// may only call async-signal-safe functions (open, write, close, _exit).
char g_marker[4096];

extern "C" void write_marker(int) {
  const int fd = ::open(g_marker, O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (fd >= 0) {
    const char text[] = "the parent's crash handler ran\n";
    [[maybe_unused]] const ssize_t n = ::write(fd, text, sizeof text - 1);
    ::close(fd);
  }
  ::_exit(0);  // as a fuzzer's handler does after recording the input
}

// Installs write_marker for `sig` in this process (as libFuzzer installs its
// crash handler) and restores the previous action when it goes.
class CrashHandler {
 public:
  CrashHandler(int sig, const fs::path& marker) : sig_(sig) {
    std::strncpy(g_marker, marker.c_str(), sizeof g_marker - 1);
    struct sigaction action {};
    action.sa_handler = write_marker;
    sigemptyset(&action.sa_mask);
    ::sigaction(sig, &action, &previous_);
  }
  ~CrashHandler() { ::sigaction(sig_, &previous_, nullptr); }
  CrashHandler(const CrashHandler&) = delete;
  CrashHandler& operator=(const CrashHandler&) = delete;

 private:
  int sig_;
  struct sigaction previous_ {};
};

TEST(IsolatedRead, ACrashInTheChildIsAnIoErrorAndNeverRunsTheParentsCrashHandler) {
  TempDir dir;
  const fs::path file = dir / "corrupt.h5";
  for (const int sig : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) {
    const fs::path marker = dir / ("handler-ran-" + std::to_string(sig));
    {
      const CrashHandler handler(sig, marker);
      const std::string message =
          cnclab::testing::io_error([&] { probe_in_child(file, [sig] { ::raise(sig); }); });
      EXPECT_NE(message.find(file.string() +
                             ": corrupt HDF5 file: the HDF5 library crashed "
                             "reading it (signal " +
                             std::to_string(sig) + ", " + ::strsignal(sig) + ")"),
                std::string::npos)
          << message;
    }
    EXPECT_FALSE(fs::exists(marker)) << "the inherited handler for signal " << sig << " ran";
  }
}

TEST(IsolatedRead, AnIgnoredFaultSignalStillEndsTheChild) {
  // SIG_IGN is inherited across fork too: a fault the parent ignores would be
  // dropped in the child, and a read that never finished taken as clean.
  TempDir dir;
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  ::sigaction(SIGFPE, &ignore, &previous);
  EXPECT_IO_ERROR(probe_in_child(dir / "f.h5", [] { ::raise(SIGFPE); }), "crashed reading it");
  ::sigaction(SIGFPE, &previous, nullptr);
}

TEST(IsolatedRead, ACleanReadReturnsAndAnIoErrorInTheChildComesBackVerbatim) {
  TempDir dir;
  EXPECT_NO_THROW(probe_in_child(dir / "ok.h5", [] {}));
  const std::string message = cnclab::testing::io_error(
      [&] { probe_in_child(dir / "bad.h5", [] { throw IoError("bad.h5: no /result group"); }); });
  EXPECT_EQ(message, "bad.h5: no /result group");
}

// Many files: one child reads on while reads are clean; a crash, an error or a
// hang is that file's alone (read again in a child of its own, where a file
// that only failed after another read is clean; otherwise the same exception
// probe_in_child gives), and a new child goes on with the next file. Which
// child read which file is told by the process ids the reads write down.
TEST(IsolatedRead, ManyFilesShareAChildUntilOneFailsAndEachFailureIsItsOwn) {
  TempDir dir;
  // (names appended, not "pid-" + to_string(i): GCC 12 warns on that in a
  // lambda, -Wrestrict, a false positive)
  const auto numbered = [&](std::string name, std::size_t i) {
    return dir / name.append(std::to_string(i));
  };
  std::vector<fs::path> files;
  for (std::size_t i = 0; i < 12; ++i) files.push_back(numbered("f", i).replace_extension(".h5"));
  bool damaged = false;  // each child's own copy
  const auto read = [&](std::size_t i) {
    std::ofstream(numbered("pids-", i), std::ios::app) << ::getpid() << "\n";
    if (i == 2) ::raise(SIGSEGV);
    if (i == 4) throw IoError("f4.h5: no /result group");
    if (i == 6) ::pause();  // until the time limit
    if (i == 7) throw std::runtime_error("bad_alloc-like");
    if (i == 9) damaged = true;  // a read that harms its process without failing
    if (i == 10 && damaged) ::raise(SIGSEGV);
  };
  const std::vector<std::exception_ptr> probed = probe_each_in_child(files, read, 0.5);
  ASSERT_EQ(probed.size(), files.size());
  const auto pids = [&](std::size_t i) {
    std::ifstream in(numbered("pids-", i));
    std::vector<long> out;
    for (long pid = 0; in >> pid;) out.push_back(pid);
    return out;
  };
  for (std::size_t i = 0; i < files.size(); ++i) {
    ASSERT_FALSE(pids(i).empty()) << "file " << i << " not read";
    for (const long pid : pids(i)) EXPECT_NE(pid, ::getpid()) << "file " << i << " in the parent";
  }
  // Children: {0, 1, 2 crashes}, {2}, {3, 4 throws}, {4}, {5, 6 hangs}, {6},
  // {7 throws: its first file, not read again}, {8, 9, 10 crashes}, {10}, {11}.
  const auto once = [&](std::size_t i) {
    EXPECT_EQ(pids(i).size(), 1u) << "file " << i;
    return pids(i).front();
  };
  const auto twice = [&](std::size_t i) {
    EXPECT_EQ(pids(i).size(), 2u) << "file " << i;
    return pids(i);
  };
  EXPECT_EQ(once(0), once(1));
  EXPECT_EQ(twice(2)[0], once(1));
  EXPECT_EQ(twice(4)[0], once(3));
  EXPECT_EQ(twice(6)[0], once(5));
  EXPECT_EQ(once(8), once(9));
  EXPECT_EQ(twice(10)[0], once(9));
  const std::vector<long> children = {once(0),     twice(2)[1], once(3), twice(4)[1],  once(5),
                                      twice(6)[1], once(7),     once(8), twice(10)[1], once(11)};
  EXPECT_EQ(std::set<long>(children.begin(), children.end()).size(), children.size());
  for (const std::size_t clean : {0, 1, 3, 5, 8, 9, 10, 11}) {
    EXPECT_FALSE(probed[clean]) << "file " << clean;
  }
  // Each failure is what probe_in_child throws for that file alone.
  const auto message = [](const std::exception_ptr& e) -> std::string {
    try {
      if (e) std::rethrow_exception(e);
    } catch (const std::exception& x) {
      return x.what();
    }
    return "";
  };
  for (const std::size_t failed : {2, 4, 6, 7}) {
    ASSERT_TRUE(probed[failed]) << "file " << failed;
    const std::string alone = cnclab::testing::io_error([&] {
      probe_in_child(
          files[failed], [&] { read(failed); }, 0.5);
    });
    EXPECT_EQ(message(probed[failed]), alone) << "file " << failed;
  }
  EXPECT_NE(message(probed[2]).find("crashed reading it (signal " + std::to_string(SIGSEGV)),
            std::string::npos);
  EXPECT_EQ(message(probed[4]), "f4.h5: no /result group");
  try {
    std::rethrow_exception(probed[6]);
  } catch (const ProbeTimedOut& e) {
    EXPECT_NE(std::string(e.what()).find(files[6].string() +
                                         ": corrupt HDF5 file: the HDF5 "
                                         "library did not finish reading it in 0.5 s"),
              std::string::npos)
        << e.what();
  } catch (...) {
    ADD_FAILURE() << "a hang is not a ProbeTimedOut";
  }
  EXPECT_EQ(message(probed[7]), files[7].string() + ": unreadable: bad_alloc-like");
  EXPECT_TRUE(probe_each_in_child({}, read).empty());
}

// read_each_isolated: the in-process value of each clean file, the probe's
// exception for the others (never read in the parent).
TEST(IsolatedRead, ReadEachIsolatedReadsCleanFilesInProcessOnly) {
  TempDir dir;
  const std::vector<fs::path> files = {dir / "a", dir / "bad", dir / "c"};
  const long parent = ::getpid();
  int parent_reads = 0;
  const std::vector<ReadOutcome<std::string>> out =
      read_each_isolated<std::string>(files, [&](const fs::path& f) -> std::string {
        if (f.filename() == "bad") throw IoError("bad: truncated");
        if (::getpid() == parent) ++parent_reads;
        return f.filename().string() + "!";
      });
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].get(), "a!");
  EXPECT_EQ(out[2].get(), "c!");
  EXPECT_EQ(parent_reads, 2);
  EXPECT_FALSE(out[1].value);
  EXPECT_IO_ERROR(out[1].get(), "bad: truncated");
}

}  // namespace
}  // namespace cnclab
