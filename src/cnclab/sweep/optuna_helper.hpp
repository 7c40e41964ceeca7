#pragma once
// The Optuna helper process of a model-based sweep (methods tpe, cmaes,
// nsga2, qmc; model_search.hpp): scripts/optuna/optuna_helper.py run by the
// system Python, one per sweep worker, talking JSON lines over its stdin and
// stdout (the messages are listed in the script).
//
// One request at a time: a request writes one line and reads one answer.
// Forked trial processes (trial_pool.hpp) inherit the pipes and report their
// epochs through them, so every request holds a POSIX record lock (fcntl
// F_SETLKW) on a private file for its write and read: record locks belong to
// a process, so the parent and its children exclude each other.
//
// Failures are clear errors, never a hang: every read waits at most
// `timeout_seconds`; a helper that exits, closes its output or answers
// something that is not a JSON object is an Error naming the script, its
// exit status and the last lines it wrote to stderr.
#include <sys/types.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace cnclab {

struct OptunaHelperOptions {
  // The Python that has Optuna: the environment's CNCLAB_PYTHON, else
  // /usr/bin/python3 (Debian's python3-optuna installs for the system
  // interpreter; a python3 found first on PATH, e.g. a pyenv, may lack it).
  std::filesystem::path interpreter;
  // The helper script; empty: scripts/optuna/optuna_helper.py in cnclab's
  // share roots (core/share_paths.hpp).
  std::filesystem::path script;
  // Longest wait for one answer (opening a study imports Optuna and reads
  // the journal: seconds on a loaded machine).
  double timeout_seconds = 300;
  // What the error says is missing when `import optuna` fails (ConfigError,
  // exit 2), e.g. "method tpe".
  std::string purpose = "a model-based sweep";

  void validate() const;  // OptionError on a non-positive timeout
};

// CNCLAB_PYTHON or /usr/bin/python3.
std::filesystem::path default_optuna_python();

class OptunaHelper {
 public:
  // Starts the helper and checks that it imports Optuna: ConfigError naming
  // the interpreter and the package python3-optuna when it cannot, Error when
  // the process cannot be started.
  explicit OptunaHelper(OptunaHelperOptions options);
  ~OptunaHelper();  // closes its input and waits (then kills) the helper
  OptunaHelper(const OptunaHelper&) = delete;
  OptunaHelper& operator=(const OptunaHelper&) = delete;

  // Sends `message` and returns the answer; Error with the helper's text
  // when it answers {"ok": false, "error": ...} (ConfigError when
  // `config_error` says the message came from the user's configuration).
  nlohmann::json request(const nlohmann::json& message, bool config_error = false);

  // Sends a raw line (tests: malformed messages) and returns the answer.
  nlohmann::json request_line(const std::string& line);

  pid_t pid() const { return pid_; }
  const std::filesystem::path& script() const { return options_.script; }

 private:
  std::string read_line();
  [[noreturn]] void died(const std::string& what);
  std::string stderr_tail() const;

  OptunaHelperOptions options_;
  pid_t pid_ = -1;
  int to_helper_ = -1, from_helper_ = -1, lock_fd_ = -1;
  std::filesystem::path stderr_file_;
  std::string buffer_;  // bytes read past the last line
};

}  // namespace cnclab
