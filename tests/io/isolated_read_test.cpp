#include "cnclab/io/isolated_read.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <string>

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

}  // namespace
}  // namespace cnclab
