#pragma once
// Child processes for end-to-end tests: spawn a program with its output
// discarded, wait for it, read a file whole, run a shell command line with
// its output captured.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

namespace cnclab::testing {

// Starts args[0] with stdout and stderr to /dev/null. Returns the pid, or -1
// and a test failure (callers must never kill(-1, ...)).
inline pid_t spawn_quiet(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0 || pid <= 0) {
    ADD_FAILURE() << "cannot spawn " << args[0];
    return -1;
  }
  return pid;
}

// The exit code, or minus the signal number that ended the process.
inline int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct ShellResult {
  int code = -1;  // exit code; -1 when the shell did not exit normally
  std::string out, err;
};

// Runs `command` with /bin/sh in `dir`, stdout and stderr captured (through
// dir/.out and dir/.err, removed afterwards).
inline ShellResult run_shell(const std::filesystem::path& dir, const std::string& command) {
  const std::filesystem::path out = dir / ".out", err = dir / ".err";
  const std::string line = "cd '" + dir.string() + "' && " + command + " >'" + out.string() +
                           "' 2>'" + err.string() + "'";
  const int status = std::system(line.c_str());
  ShellResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

}  // namespace cnclab::testing
