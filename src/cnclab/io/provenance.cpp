#include "cnclab/io/provenance.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <Eigen/Core>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iterator>
#include <sstream>

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
  p.command_line = process_command_line();
  p.cpu_at_start = process_cpu_seconds();
  return p;
}

namespace {
// POSIX shell quoting: words of safe characters as they are, others in '...'.
std::string shell_quote(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                              "0123456789_-+=.,/:@%^") == std::string::npos)
    return word;
  std::string out = "'";
  for (const char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Standard output of `command` (stderr discarded), trailing newlines
// dropped; false when it cannot run or exits non-zero.
bool run_capture(const std::string& command, std::string& output) {
  output.clear();
  FILE* pipe = ::popen((command + " 2>/dev/null").c_str(), "r");
  if (pipe == nullptr) return false;
  char buf[4096];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) output.append(buf, n);
  const int status = ::pclose(pipe);
  while (!output.empty() && output.back() == '\n') output.pop_back();
  return status == 0;
}
}  // namespace

std::string process_command_line() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  if (!in) return "";
  const std::string raw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string out;
  std::size_t begin = 0;
  while (begin < raw.size()) {
    std::size_t end = raw.find('\0', begin);
    if (end == std::string::npos) end = raw.size();
    if (!out.empty()) out += ' ';
    out += shell_quote(raw.substr(begin, end - begin));
    begin = end + 1;
  }
  return out;
}

double process_cpu_seconds() {
  rusage usage{};
  if (::getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

ProjectState project_git_state(const std::filesystem::path& dir) {
  const std::string git = "git -C " + shell_quote(dir.empty() ? "." : dir.string());
  ProjectState state;
  std::string head, changes;
  if (!run_capture(git + " rev-parse --verify HEAD", head) || head.size() != 40) return state;
  if (!run_capture(git + " status --porcelain --untracked-files=no", changes)) return state;
  state.commit = head;
  state.dirty = changes.empty() ? "no" : "yes";
  return state;
}

void set_project(Provenance& p, const std::filesystem::path& dir) {
  std::error_code ec;
  const auto absolute = std::filesystem::absolute(dir.empty() ? "." : dir, ec);
  std::filesystem::path folder = ec ? dir : absolute.lexically_normal();
  if (folder.has_parent_path() && folder.filename().empty()) folder = folder.parent_path();  // "a/"
  p.project_dir = folder.string();
  const ProjectState state = project_git_state(p.project_dir);
  p.project_commit = state.commit;
  p.project_dirty = state.dirty;
}

void finish_provenance(Provenance& p) {
  p.end_utc = utc_now_iso8601();
  p.cpu_seconds = process_cpu_seconds() - p.cpu_at_start;
}

namespace {
std::string seconds_text(double s) {
  std::ostringstream out;
  out.precision(s < 10 ? 3 : 4);
  out << s << " s";
  return out.str();
}
}  // namespace

std::vector<std::pair<std::string, std::string>> provenance_lines(const Provenance& p) {
  std::vector<std::pair<std::string, std::string>> lines;
  lines.emplace_back("cnclab", p.cnclab_version + " (git " + p.git_commit +
                                   (p.isa.empty() ? "" : ", kernels " + p.isa) + ")");
  lines.emplace_back("run", p.start_utc + " -> " + p.end_utc + " on " + p.host);
  std::string time = "wall " + seconds_text(p.wall_seconds);
  if (p.cpu_seconds >= 0) time += ", CPU " + seconds_text(p.cpu_seconds);
  lines.emplace_back("time", time);
  if (!p.command_line.empty()) lines.emplace_back("command", p.command_line);
  if (!p.profile.empty()) lines.emplace_back("profile", p.profile);
  for (const auto& o : p.overrides) lines.emplace_back("override", o);
  if (!p.project_dir.empty()) {
    lines.emplace_back(
        "project",
        p.project_dir + (p.project_commit.empty()
                             ? " (not a git repository)"
                             : " (git " + p.project_commit +
                                   (p.project_dirty == "yes" ? ", dirty)" : ", clean)")));
  }
  return lines;
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
  f.set_attribute(g, "command_line", p.command_line);
  std::string overrides;
  for (const auto& o : p.overrides) overrides += (overrides.empty() ? "" : "\n") + o;
  f.set_attribute(g, "overrides", overrides);
  f.set_attribute(g, "profile", p.profile);
  f.set_attribute(g, "project_dir", p.project_dir);
  f.set_attribute(g, "project_commit", p.project_commit);
  f.set_attribute(g, "project_dirty", p.project_dirty);
  f.set_attribute(g, "cpu_seconds", p.cpu_seconds);
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
  // Stored since results recorded how they were made; older files lack them.
  const auto text = [&](const char* name) {
    return f.has_attribute(g, name) ? f.attribute_string(g, name) : std::string();
  };
  p.command_line = text("command_line");
  std::istringstream overrides(text("overrides"));
  for (std::string line; std::getline(overrides, line);)
    if (!line.empty()) p.overrides.push_back(line);
  p.profile = text("profile");
  p.project_dir = text("project_dir");
  p.project_commit = text("project_commit");
  p.project_dirty = text("project_dirty");
  if (f.has_attribute(g, "cpu_seconds")) p.cpu_seconds = f.attribute_double(g, "cpu_seconds");
  for (const auto& name : f.attribute_names(g + "/seeds")) {
    p.derived_seeds[name] = parse_seed(f, g + "/seeds", name);
  }
  for (const auto& name : f.attribute_names(g + "/libraries")) {
    p.libraries[name] = f.attribute_string(g + "/libraries", name);
  }
  return p;
}

}  // namespace cnclab
