#pragma once
// Progress of long work on stderr. On a terminal: one bar redrawn in place
// with rate and ETA. Otherwise (logs, CI): a plain line every
// `plain_interval_seconds`. Quiet: nothing. The mode is chosen by the caller
// (from --quiet and isatty), never from global state.
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
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

// How long work in named stages reports to its caller, without knowing how
// (or whether) it is shown: `done` of `total` units of `stage` finished.
// Work calls it at its own pace; an empty callback means nobody listens.
using ProgressCallback =
    std::function<void(const std::string& stage, std::size_t done, std::size_t total)>;

// Shows a ProgressCallback's reports: one Progress per stage, labelled
// "<label>: <stage>", finished when another stage starts or at destruction.
class StagedProgress {
 public:
  StagedProgress(std::string label, std::ostream& out, Progress::Options options = {});
  void report(const std::string& stage, std::size_t done, std::size_t total);
  // A callback reporting here; valid while this object lives.
  ProgressCallback callback();

 private:
  std::string label_, stage_;
  std::ostream& out_;
  Progress::Options options_;
  std::unique_ptr<Progress> current_;
};

}  // namespace cnclab
