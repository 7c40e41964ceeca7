#include "cnclab/sweep/slurm_queue.hpp"

#include <set>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/sweep/slurm_tools.hpp"

namespace cnclab {
namespace {

std::string trimmed_first_line(const std::string& text) {
  const std::string line = text.substr(0, text.find('\n'));
  const auto b = line.find_first_not_of(" \t");
  return b == std::string::npos ? "" : line.substr(b, line.find_last_not_of(" \t\r") - b + 1);
}

// "a|b|c" -> {"a", "b", "c"}.
std::vector<std::string> split_bars(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  std::string f;
  while (std::getline(in, f, '|')) fields.push_back(f);
  return fields;
}

}  // namespace

SlurmPhase slurm_phase(const std::string& state_text) {
  // sacct writes "CANCELLED by 0"; squeue "CANCELLED".
  const std::string state = state_text.substr(0, state_text.find(' '));
  static const std::set<std::string> running = {"RUNNING", "CONFIGURING", "COMPLETING", "SIGNALING",
                                                "STAGE_OUT"};
  static const std::set<std::string> ended = {"COMPLETED", "CANCELLED", "FAILED",
                                              "TIMEOUT",   "NODE_FAIL", "BOOT_FAIL",
                                              "DEADLINE",  "REVOKED",   "OUT_OF_MEMORY"};
  if (running.count(state)) return SlurmPhase::running;
  if (ended.count(state)) return SlurmPhase::ended;
  return SlurmPhase::queued;
}

SlurmTaskStates parse_squeue_tasks(const std::string& text) {
  SlurmTaskStates tasks;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto f = split_bars(line);
    if (f.size() < 3 || f[1] == "N/A") continue;  // not an array task
    tasks[f[0] + "_" + f[1]] = f[2];
  }
  return tasks;
}

SlurmTaskStates parse_squeue_jobs(const std::string& text) {
  SlurmTaskStates jobs;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto f = split_bars(line);
    if (f.size() >= 3 && f[1] == "N/A") jobs[f[0]] = f[2];
  }
  return jobs;
}

SlurmTaskStates parse_sacct_tasks(const std::string& text) {
  // JobID|State with JobID "123_4" (one task), "123_[5-9]" (tasks not yet
  // started, all pending) or "123" (not an array).
  SlurmTaskStates tasks;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto f = split_bars(line);
    if (f.size() < 2) continue;
    const auto us = f[0].find('_');
    if (us == std::string::npos || f[0].find('[') != std::string::npos) continue;
    tasks[f[0]] = f[1];
  }
  return tasks;
}

namespace {

// squeue's "<array job>|<task or N/A>|<state>" lines of the caller's jobs.
std::string squeue_lines() {
  const ToolRun r = run_tool({"squeue", "-h", "-r", "--me", "-t", "all", "-o", "%F|%K|%T"});
  if (r.exit_code != 0) {
    throw Error("squeue failed (exit " + std::to_string(r.exit_code) +
                "): " + trimmed_first_line(r.err + r.out) +
                "; cannot tell which jobs are queued or running");
  }
  return r.out;
}

}  // namespace

SlurmTaskStates squeue_tasks() {
  return parse_squeue_tasks(squeue_lines());
}

SlurmTaskStates squeue_jobs() {
  return parse_squeue_jobs(squeue_lines());
}

std::optional<SlurmTaskStates> sacct_tasks(const std::vector<std::string>& array_jobs,
                                           std::string& why) {
  if (array_jobs.empty()) return SlurmTaskStates{};
  if (!find_on_path("sacct")) {
    why = "sacct not on PATH";
    return std::nullopt;
  }
  std::string ids;
  for (const auto& j : array_jobs) ids += (ids.empty() ? "" : ",") + j;
  const ToolRun r = run_tool({"sacct", "-n", "-P", "-X", "-j", ids, "-o", "JobID,State"});
  if (r.exit_code != 0) {
    why = "sacct: " + trimmed_first_line(r.err + r.out);
    return std::nullopt;
  }
  return parse_sacct_tasks(r.out);
}

}  // namespace cnclab
