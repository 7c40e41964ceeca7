#pragma once
// Who made a result, from what, when: stored in /provenance of every result.
//
// Layout under `group` (all scalar string attributes unless noted):
//   <group>            cnclab_version, git_commit, master_seed (decimal text),
//                      host, isa, start_utc, end_utc, wall_seconds (float64),
//                      status, failure_reason
//                      and, when known (absent in older files):
//                      command_line, overrides (one `key=value` a line),
//                      profile, project_dir, project_commit,
//                      project_dirty ("yes" | "no"), cpu_seconds (float64)
//   <group>/seeds      one attribute per derived stream: name = seed (decimal text)
//   <group>/libraries  one attribute per library: name = version
// Seeds are decimal text because common readers map HDF5 integers to
// signed 64-bit and a uint64 seed may not fit.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace cnclab {

class H5File;

struct Provenance {
  std::string cnclab_version;
  std::string git_commit;  // embedded at build time; "-dirty" when built from a modified tree
  std::uint64_t master_seed = 0;
  std::map<std::string, std::uint64_t> derived_seeds;  // stream name -> seed
  std::string host;
  // The instruction-set level the hot kernels ran at (core/isa.hpp:
  // baseline, v3, v4 or native): results of one level agree bit for bit
  // across machines, of different levels to rounding. Empty when read from
  // a file written before the level was recorded (those ran the baseline's
  // kernels, or native ones in a CNCLAB_NATIVE_ARCH build).
  std::string isa;
  std::string start_utc;  // ISO 8601, e.g. 2026-11-24T19:30:00Z
  std::string end_utc;
  double wall_seconds = 0;
  std::map<std::string, std::string> libraries;  // name -> version
  std::string status;                            // "complete" | "failed"
  std::string failure_reason;

  // How it was made; empty (cpu_seconds -1) when unknown, as in files
  // written before these were stored.
  std::string command_line;            // this process's argv, shell-quoted
  std::vector<std::string> overrides;  // `key=value` as given, in order
  std::string profile;                 // --profile ("" = none)
  std::string project_dir;             // the experiment file's folder
  std::string project_commit;          // git HEAD there; "" when not in a git repository
  std::string project_dirty;           // "yes" | "no" (tracked files changed); "" as above
  double cpu_seconds = -1;             // user + system CPU time of this process during the run
  double cpu_at_start = 0;             // process CPU time at make_provenance (not stored)
};

// The git state of the repository holding `dir` (git on PATH; nothing when
// `dir` is not in a repository or git is missing). Dirty means a tracked file
// differs from HEAD: untracked files are left out, as results/ and datasets/
// may not be ignored in a user's project and every run would be "dirty".
struct ProjectState {
  std::string commit;  // 40 hex digits
  std::string dirty;   // "yes" | "no"
};
ProjectState project_git_state(const std::filesystem::path& dir);
// Sets project_dir, project_commit and project_dirty for `dir`.
void set_project(Provenance& p, const std::filesystem::path& dir);

// argv of this process from /proc/self/cmdline, each word shell-quoted when
// it needs it; "" where that file does not exist.
std::string process_command_line();
// User + system CPU seconds of this process (all its threads) so far.
double process_cpu_seconds();
// end_utc = now, cpu_seconds = CPU time since make_provenance.
void finish_provenance(Provenance& p);
// What `show` and reports print of a provenance: (label, text) in order;
// fields that are unknown are left out. The first is ("cnclab",
// "0.1.0 (git 1a2b3c4d5e6f, kernels v4)"), no kernel level for files without one.
std::vector<std::pair<std::string, std::string>> provenance_lines(const Provenance& p);

// Version, commit, host, kernel level, libraries, start time, command line
// and the CPU time so far filled in.
Provenance make_provenance(std::uint64_t master_seed);

std::string utc_now_iso8601();
std::string host_name();
// Eigen, HDF5, yaml-cpp, CLI11 versions this binary was built with.
std::map<std::string, std::string> library_versions();

void write_provenance(H5File& file, const std::string& group, const Provenance& p);
Provenance read_provenance(const H5File& file, const std::string& group);

}  // namespace cnclab
