#include "cnclab/report/run_index.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unordered_map>

#include "cnclab/core/error.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/report/compare.hpp"

namespace cnclab {
namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

constexpr const char* kIndexFormat = "cnclab-runs-index";
constexpr int kIndexVersion = 1;

Json number_json(double v) {
  return std::isfinite(v) ? Json(v) : Json(nullptr);
}
double json_number(const Json& j) {
  return j.is_number() ? j.get<double>() : std::numeric_limits<double>::quiet_NaN();
}

Json provenance_json(const Provenance& p) {
  return {{"cnclab_version", p.cnclab_version},
          {"git_commit", p.git_commit},
          {"master_seed", std::to_string(p.master_seed)},
          {"host", p.host},
          {"start_utc", p.start_utc},
          {"end_utc", p.end_utc},
          {"wall_seconds", number_json(p.wall_seconds)},
          {"cpu_seconds", number_json(p.cpu_seconds)},
          {"status", p.status},
          {"failure_reason", p.failure_reason},
          {"command_line", p.command_line},
          {"overrides", p.overrides},
          {"profile", p.profile},
          {"project_dir", p.project_dir},
          {"project_commit", p.project_commit},
          {"project_dirty", p.project_dirty}};
}

Provenance provenance_from(const Json& j) {
  Provenance p;
  p.cnclab_version = j.at("cnclab_version").get<std::string>();
  p.git_commit = j.at("git_commit").get<std::string>();
  p.master_seed = std::stoull(j.at("master_seed").get<std::string>());
  p.host = j.at("host").get<std::string>();
  p.start_utc = j.at("start_utc").get<std::string>();
  p.end_utc = j.at("end_utc").get<std::string>();
  p.wall_seconds = json_number(j.at("wall_seconds"));
  p.cpu_seconds = j.at("cpu_seconds").is_number() ? j.at("cpu_seconds").get<double>() : -1;
  p.status = j.at("status").get<std::string>();
  p.failure_reason = j.at("failure_reason").get<std::string>();
  p.command_line = j.at("command_line").get<std::string>();
  p.overrides = j.at("overrides").get<std::vector<std::string>>();
  p.profile = j.at("profile").get<std::string>();
  p.project_dir = j.at("project_dir").get<std::string>();
  p.project_commit = j.at("project_commit").get<std::string>();
  p.project_dirty = j.at("project_dirty").get<std::string>();
  return p;
}

Json run_json(const IndexedRun& r) {
  Json j = {{"file", r.file.string()}, {"size", r.size}, {"mtime_ns", r.mtime_ns}};
  if (!r.error.empty()) {
    j["error"] = r.error;
    return j;
  }
  const ResultSummary& s = r.summary;
  Json metrics = Json::object();
  for (const auto& [name, value] : s.metrics) metrics[name] = number_json(value);
  Json config = Json::array();
  for (const auto& [key, value] : r.config) config.push_back({key, value});
  j["kind"] = s.kind;
  j["experiment"] = s.experiment;
  j["config_hash"] = s.config_hash;
  j["config"] = std::move(config);
  j["metrics"] = std::move(metrics);
  j["units"] = s.metric_units;
  j["warnings"] = s.warnings;
  j["provenance"] = provenance_json(s.provenance);
  j["dataset_file"] = s.dataset_file;
  j["upstream_files"] = s.upstream_files;
  j["output_files"] = s.output_files;
  return j;
}

IndexedRun run_from(const Json& j) {
  IndexedRun r;
  r.file = j.at("file").get<std::string>();
  r.size = j.at("size").get<std::uintmax_t>();
  r.mtime_ns = j.at("mtime_ns").get<std::int64_t>();
  if (j.contains("error")) {
    r.error = j.at("error").get<std::string>();
    return r;
  }
  ResultSummary& s = r.summary;
  s.kind = j.at("kind").get<std::string>();
  s.experiment = j.at("experiment").get<std::string>();
  s.config_hash = j.at("config_hash").get<std::string>();
  for (const auto& kv : j.at("config")) {
    r.config.emplace_back(kv.at(0).get<std::string>(), kv.at(1).get<std::string>());
  }
  for (const auto& [name, value] : j.at("metrics").items()) s.metrics[name] = json_number(value);
  s.metric_units = j.at("units").get<std::map<std::string, std::string>>();
  s.warnings = j.at("warnings").get<std::vector<std::string>>();
  s.provenance = provenance_from(j.at("provenance"));
  s.dataset_file = j.at("dataset_file").get<std::string>();
  s.upstream_files = j.at("upstream_files").get<std::vector<std::string>>();
  s.output_files = j.at("output_files").get<std::vector<std::string>>();
  return r;
}

// The entries of a readable index by file; empty (and `note` set) otherwise.
std::unordered_map<std::string, IndexedRun> load_index(const fs::path& file, std::string& note) {
  std::unordered_map<std::string, IndexedRun> entries;
  std::error_code ec;
  if (file.empty() || !fs::exists(file, ec)) return entries;
  try {
    std::ifstream in(file);
    const Json j = Json::parse(in);
    if (j.at("format") != kIndexFormat || j.at("version") != kIndexVersion) {
      note = file.string() + ": another format or version; rebuilt";
      return entries;
    }
    for (const auto& run : j.at("runs")) {
      IndexedRun r = run_from(run);
      entries.emplace(r.file.string(), std::move(r));
    }
  } catch (const std::exception& e) {
    note = file.string() + ": unreadable (" + e.what() + "); rebuilt";
    entries.clear();
  }
  return entries;
}

struct FoundFile {
  fs::path path;
  std::uintmax_t size = 0;
  std::int64_t mtime_ns = 0;
};

bool is_result_candidate(const fs::path& p) {
  return p.extension() == ".h5" && !is_partial_path(p) && p.filename() != "summary.h5";
}

void add_found(const fs::path& p, std::vector<FoundFile>& out) {
  std::error_code ec;
  const auto size = fs::file_size(p, ec);
  if (ec) return;
  const auto time = fs::last_write_time(p, ec);
  if (ec) return;
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(time.time_since_epoch());
  out.push_back({fs::absolute(p).lexically_normal(), size, static_cast<std::int64_t>(ns.count())});
}

std::vector<FoundFile> find_files(const std::vector<fs::path>& inputs) {
  std::vector<FoundFile> found;
  for (const auto& input : inputs) {
    std::error_code ec;
    if (fs::is_regular_file(input, ec)) {
      add_found(input, found);
      continue;
    }
    if (!fs::is_directory(input, ec)) {
      throw ConfigError(input.string() + ": no such result file or folder");
    }
    fs::recursive_directory_iterator it(input, fs::directory_options::skip_permission_denied, ec);
    for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      if (it->is_regular_file(ec) && is_result_candidate(it->path())) add_found(it->path(), found);
    }
    if (ec) throw IoError(input.string() + ": cannot list: " + ec.message());
  }
  std::sort(found.begin(), found.end(),
            [](const FoundFile& a, const FoundFile& b) { return a.path < b.path; });
  found.erase(std::unique(found.begin(), found.end(),
                          [](const FoundFile& a, const FoundFile& b) { return a.path == b.path; }),
              found.end());
  return found;
}

bool under(const fs::path& file, const std::vector<fs::path>& roots) {
  const std::string f = file.string();
  for (const auto& r : roots) {
    const std::string root = r.string();
    if (f == root || (f.compare(0, root.size(), root) == 0 && f.size() > root.size() &&
                      (root.back() == '/' || f[root.size()] == '/')))
      return true;
  }
  return false;
}

void save_index(const fs::path& file, const std::unordered_map<std::string, IndexedRun>& kept,
                const std::vector<IndexedRun>& scanned, std::string& note) {
  Json runs = Json::array();
  for (const auto& [name, r] : kept) runs.push_back(run_json(r));
  for (const auto& r : scanned) runs.push_back(run_json(r));
  const Json j = {{"format", kIndexFormat}, {"version", kIndexVersion}, {"runs", std::move(runs)}};
  try {
    write_text_atomically(file, j.dump() + "\n");
  } catch (const Error& e) {
    note = std::string(e.what()) + " (listing works without it, only slower)";
  }
}

}  // namespace

fs::path runs_index_path(const fs::path& results_dir) {
  return results_dir / ".runs-index.json";
}

RunScan scan_runs(const std::vector<fs::path>& inputs, const fs::path& index_file) {
  RunScan scan;
  scan.index_file = index_file;
  auto index = load_index(index_file, scan.index_note);
  const std::vector<FoundFile> found = find_files(inputs);

  std::vector<IndexedRun> all(found.size());
  std::vector<fs::path> to_read;
  std::vector<std::size_t> to_read_at;
  for (std::size_t i = 0; i < found.size(); ++i) {
    const FoundFile& f = found[i];
    const auto it = index.find(f.path.string());
    if (it != index.end() && it->second.size == f.size && it->second.mtime_ns == f.mtime_ns) {
      all[i] = std::move(it->second);
      ++scan.reused;
    } else {
      all[i].file = f.path;
      all[i].size = f.size;
      all[i].mtime_ns = f.mtime_ns;
      to_read.push_back(f.path);
      to_read_at.push_back(i);
    }
    if (it != index.end()) index.erase(it);
  }
  const auto summaries = read_result_summaries(to_read);
  for (std::size_t k = 0; k < summaries.size(); ++k) {
    IndexedRun& r = all[to_read_at[k]];
    r.error = summaries[k].error;
    if (!r.error.empty()) continue;
    r.summary = summaries[k].summary;
    try {
      r.config = flatten_config(r.summary.resolved_yaml, false);
    } catch (const Error& e) {
      r.error = r.file.string() + ": " + e.what();
    }
    r.summary.resolved_yaml.clear();
  }
  scan.read = to_read.size();

  if (!index_file.empty()) {
    // Entries of folders not listed now stay; those of listed folders whose
    // files are gone go.
    std::vector<fs::path> roots;
    for (const auto& input : inputs) roots.push_back(fs::absolute(input).lexically_normal());
    std::size_t dropped = 0;
    for (auto it = index.begin(); it != index.end();) {
      if (under(it->second.file, roots)) {
        it = index.erase(it);
        ++dropped;
      } else {
        ++it;
      }
    }
    std::error_code ec;
    if (scan.read > 0 || dropped > 0 || !scan.index_note.empty() || !fs::exists(index_file, ec))
      save_index(index_file, index, all, scan.index_note);
  }
  for (auto& r : all) (r.error.empty() ? scan.runs : scan.unreadable).push_back(std::move(r));
  return scan;
}

}  // namespace cnclab
