#pragma once
// Who made a result, from what, when: stored in /provenance of every result.
//
// Layout under `group` (all scalar string attributes unless noted):
//   <group>            cnclab_version, git_commit, master_seed (decimal text),
//                      host, isa, start_utc, end_utc, wall_seconds (float64),
//                      status, failure_reason
//   <group>/seeds      one attribute per derived stream: name = seed (decimal text)
//   <group>/libraries  one attribute per library: name = version
// Seeds are decimal text because common readers map HDF5 integers to
// signed 64-bit and a uint64 seed may not fit.
#include <cstdint>
#include <map>
#include <string>

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
};

// Version, commit, host, kernel level, libraries and start time filled in.
Provenance make_provenance(std::uint64_t master_seed);

std::string utc_now_iso8601();
std::string host_name();
// Eigen, HDF5, yaml-cpp, CLI11 versions this binary was built with.
std::map<std::string, std::string> library_versions();

// "0.1.0 (git 1a2b3c4d5e6f, kernels v4)": what made the result, as `show`
// and `cnclab version` print it (no kernel level for files without one).
std::string version_text(const Provenance& p);

void write_provenance(H5File& file, const std::string& group, const Provenance& p);
Provenance read_provenance(const H5File& file, const std::string& group);

}  // namespace cnclab
