#include "cnclab/io/provenance.hpp"

#include <unistd.h>

#include <Eigen/Core>
#include <charconv>
#include <chrono>
#include <ctime>

#include "cnclab/build_info.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/isa.hpp"
#include "cnclab/io/h5.hpp"

namespace cnclab {

std::string utc_now_iso8601() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string host_name() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "unknown";
  return buf;
}

std::map<std::string, std::string> library_versions() {
  return {
      {"Eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) +
                    "." + std::to_string(EIGEN_MINOR_VERSION)},
      {"HDF5", hdf5_version()},
      {"yaml-cpp", CNCLAB_YAML_CPP_VERSION},
      {"CLI11", CNCLAB_CLI11_VERSION},
  };
}

Provenance make_provenance(std::uint64_t master_seed) {
  Provenance p;
  p.cnclab_version = build::kVersion;
  p.git_commit = build::kGitCommit;
  p.master_seed = master_seed;
  p.host = host_name();
  p.isa = to_string(active_isa());
  p.start_utc = utc_now_iso8601();
  p.libraries = library_versions();
  return p;
}

std::string version_text(const Provenance& p) {
  return p.cnclab_version + " (git " + p.git_commit + (p.isa.empty() ? "" : ", kernels " + p.isa) +
         ")";
}

void write_provenance(H5File& f, const std::string& g, const Provenance& p) {
  f.create_group(g);
  f.set_attribute(g, "cnclab_version", p.cnclab_version);
  f.set_attribute(g, "git_commit", p.git_commit);
  f.set_attribute(g, "master_seed", std::to_string(p.master_seed));
  f.set_attribute(g, "host", p.host);
  f.set_attribute(g, "isa", p.isa);
  f.set_attribute(g, "start_utc", p.start_utc);
  f.set_attribute(g, "end_utc", p.end_utc);
  f.set_attribute(g, "wall_seconds", p.wall_seconds);
  f.set_attribute(g, "status", p.status);
  f.set_attribute(g, "failure_reason", p.failure_reason);
  f.create_group(g + "/seeds");
  for (const auto& [name, seed] : p.derived_seeds)
    f.set_attribute(g + "/seeds", name, std::to_string(seed));
  f.create_group(g + "/libraries");
  for (const auto& [name, version] : p.libraries) f.set_attribute(g + "/libraries", name, version);
}

namespace {
std::uint64_t parse_seed(const H5File& f, const std::string& object, const std::string& attr) {
  const std::string text = f.attribute_string(object, attr);
  std::uint64_t value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || ptr != text.data() + text.size() || text.empty()) {
    throw IoError(f.path().string() + ": " + object + ": attribute '" + attr + "' = '" + text +
                  "' is not a seed");
  }
  return value;
}
}  // namespace

Provenance read_provenance(const H5File& f, const std::string& g) {
  Provenance p;
  p.cnclab_version = f.attribute_string(g, "cnclab_version");
  p.git_commit = f.attribute_string(g, "git_commit");
  p.master_seed = parse_seed(f, g, "master_seed");
  p.host = f.attribute_string(g, "host");
  if (f.has_attribute(g, "isa")) p.isa = f.attribute_string(g, "isa");
  p.start_utc = f.attribute_string(g, "start_utc");
  p.end_utc = f.attribute_string(g, "end_utc");
  p.wall_seconds = f.attribute_double(g, "wall_seconds");
  p.status = f.attribute_string(g, "status");
  p.failure_reason = f.attribute_string(g, "failure_reason");
  for (const auto& name : f.attribute_names(g + "/seeds")) {
    p.derived_seeds[name] = parse_seed(f, g + "/seeds", name);
  }
  for (const auto& name : f.attribute_names(g + "/libraries")) {
    p.libraries[name] = f.attribute_string(g + "/libraries", name);
  }
  return p;
}

}  // namespace cnclab
