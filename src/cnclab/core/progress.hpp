#pragma once
// Progress of long work on stderr. On a terminal: one bar redrawn in place
// with rate and ETA. Otherwise (logs, CI): a plain line every
// `plain_interval_seconds`. Quiet: nothing. The mode is chosen by the caller
// (from --quiet and isatty), never from global state.
#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>

namespace cnclab {

enum class ProgressMode { automatic, terminal, plain, quiet };

class Progress {
 public:
  struct Options {
    ProgressMode mode = ProgressMode::automatic;  // automatic: terminal iff stderr is a tty
    double plain_interval_seconds = 5.0;          // plain mode: seconds between lines
    double redraw_interval_seconds = 0.1;         // terminal mode: seconds between redraws
  };

  Progress(std::string label, std::size_t total, std::ostream& out, Options options);
  Progress(std::string label, std::size_t total, std::ostream& out)
      : Progress(std::move(label), total, out, Options{}) {}
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // `done` units of `total` finished; `status` is appended (e.g. "loss 0.012").
  void update(std::size_t done, const std::string& status = "");
  // Final line (terminal: ends the bar with a newline). Called by the destructor.
  void finish(const std::string& status = "");

  // "1h02m", "3m05s", "12.3s".
  static std::string format_duration(double seconds);

 private:
  void draw(bool final_line);

  std::string label_;
  std::size_t total_;
  std::ostream& out_;
  ProgressMode mode_;
  Options options_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  std::size_t done_ = 0;
  std::string status_;
  bool finished_ = false;
  bool drawn_ = false;
};

}  // namespace cnclab
