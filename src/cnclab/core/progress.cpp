#include "cnclab/core/progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace cnclab {

Progress::Progress(std::string label, std::size_t total, std::ostream& out, Options options)
    : label_(std::move(label)),
      total_(total),
      out_(out),
      mode_(options.mode),
      options_(options),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {
  if (mode_ == ProgressMode::automatic) {
    mode_ = ::isatty(STDERR_FILENO) ? ProgressMode::terminal : ProgressMode::plain;
  }
}

Progress::~Progress() {
  if (!finished_) finish();
}

std::string Progress::format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  char buf[32];
  if (seconds < 60) {
    std::snprintf(buf, sizeof buf, "%.1fs", seconds);
  } else if (seconds < 3600) {
    const int s = static_cast<int>(seconds);
    std::snprintf(buf, sizeof buf, "%dm%02ds", s / 60, s % 60);
  } else {
    const int m = static_cast<int>(seconds / 60);
    std::snprintf(buf, sizeof buf, "%dh%02dm", m / 60, m % 60);
  }
  return buf;
}

void Progress::update(std::size_t done, const std::string& status) {
  done_ = done;
  status_ = status;
  if (mode_ == ProgressMode::quiet) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_draw_).count();
  const double interval = mode_ == ProgressMode::terminal ? options_.redraw_interval_seconds
                                                          : options_.plain_interval_seconds;
  if (since < interval) return;
  last_draw_ = now;
  draw(false);
}

void Progress::finish(const std::string& status) {
  if (finished_) return;
  finished_ = true;
  if (!status.empty()) status_ = status;
  if (mode_ == ProgressMode::quiet) return;
  // Plain mode only reports the end of work that took long enough to report.
  if (mode_ == ProgressMode::plain && !drawn_) return;
  draw(true);
}

void Progress::draw(bool final_line) {
  drawn_ = true;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double fraction = total_ ? static_cast<double>(done_) / static_cast<double>(total_) : 1.0;
  const double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : NAN;
  std::ostringstream line;
  line << label_ << " ";
  if (mode_ == ProgressMode::terminal) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    line << "[" << std::string(filled, '#') << std::string(kWidth - filled, '.') << "] ";
  }
  line << done_ << "/" << total_ << " (" << static_cast<int>(fraction * 100) << "%) "
       << format_duration(elapsed);
  if (!final_line) line << " ETA " << format_duration(eta);
  if (!status_.empty()) line << "  " << status_;
  if (mode_ == ProgressMode::terminal) {
    out_ << "\r" << line.str() << "\033[K";
    if (final_line) out_ << "\n";
  } else {
    out_ << line.str() << "\n";
  }
  out_.flush();
}

StagedProgress::StagedProgress(std::string label, std::ostream& out, Progress::Options options)
    : label_(std::move(label)), out_(out), options_(options) {}

void StagedProgress::report(const std::string& stage, std::size_t done, std::size_t total) {
  if (!current_ || stage != stage_) {
    current_.reset();  // finishes the previous stage's line
    stage_ = stage;
    current_ = std::make_unique<Progress>(label_ + ": " + stage, total, out_, options_);
  }
  current_->update(done);
}

ProgressCallback StagedProgress::callback() {
  return [this](const std::string& stage, std::size_t done, std::size_t total) {
    report(stage, done, total);
  };
}

}  // namespace cnclab
