#include "cnclab/report/garbage.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>

#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/data/dataset_file.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/spec.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/isolated_read.hpp"
#include "cnclab/report/run_index.hpp"
#include "cnclab/sweep/sweep_plan.hpp"

namespace cnclab {
namespace fs = std::filesystem;

namespace {

fs::path normal(const fs::path& p) {
  return fs::absolute(p).lexically_normal();
}

// What the experiment files produce now: config hashes, names, datasets.
struct Current {
  std::set<std::string> hashes;
  std::set<std::string> names;
  std::set<std::string> dataset_names;  // cache file names (content-hashed)
};

// The profiles results may have been made with: none, each folder name of
// the results root, each profile a result recorded, and each `profiles:`
// entry at the top of an experiment file.
std::set<std::string> candidate_profiles(const GcOptions& o, const RunScan& scan) {
  std::set<std::string> profiles = {""};
  std::error_code ec;
  if (fs::is_directory(o.results_dir, ec)) {
    for (const auto& e : fs::directory_iterator(o.results_dir, ec)) {
      if (e.is_directory(ec)) profiles.insert(e.path().filename().string());
    }
  }
  for (const auto& r : scan.runs) profiles.insert(r.summary.provenance.profile);
  for (const auto& file : o.experiments) {
    try {
      const YAML::Node declared = YAML::LoadFile(file.string())["profiles"];
      if (declared && declared.IsMap()) {
        for (const auto& entry : declared) profiles.insert(entry.first.as<std::string>());
      }
    } catch (const YAML::Exception&) {
      // load_experiment below names the problem
    }
  }
  return profiles;
}

Current current_outputs(const GcOptions& o, const std::set<std::string>& profiles) {
  Current c;
  for (const auto& file : o.experiments) {
    const std::string kind = experiment_kind(file);
    for (const auto& profile : profiles) {
      std::string yaml;
      if (kind == "train") {
        const LoadedExperiment e =
            load_experiment(file, std::vector<std::string>{}, std::nullopt, profile);
        yaml = e.resolved_yaml;
        c.dataset_names.insert(
            dataset_cache_file(e.spec.dataset, generator_seed(e.spec), o.datasets_dir)
                .filename()
                .string());
      } else {
        JobContext context;
        context.options.profile = profile;
        context.options.results_dir = o.results_dir;
        context.options.datasets_dir = o.datasets_dir;
        yaml = find_job_kind(kind)->resolved_yaml(file, context);
      }
      c.hashes.insert(hash_hex(yaml));
      const YAML::Node root = YAML::Load(yaml);
      if (root["name"]) c.names.insert(root["name"].as<std::string>());
    }
  }
  return c;
}

std::uintmax_t size_of(const fs::path& p) {
  std::error_code ec;
  if (fs::is_regular_file(p, ec)) return fs::file_size(p, ec);
  std::uintmax_t total = 0;
  for (fs::recursive_directory_iterator it(p, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_regular_file(ec)) total += it->file_size(ec);
  }
  return total;
}

// The sweep folder holding `file` (an ancestor with sweep.yaml below `root`), or "".
fs::path sweep_folder_of(const fs::path& file, const fs::path& root) {
  for (fs::path d = file.parent_path(); d.string().size() > root.string().size();
       d = d.parent_path()) {
    std::error_code ec;
    if (fs::exists(d / "sweep.yaml", ec)) return d;
    if (d == d.parent_path()) break;
  }
  return {};
}

// The root attribute `format` of an HDF5 file, read safely; "" when unreadable.
std::string hdf5_format(const fs::path& file) {
  const auto read = [&] {
    const H5File f = H5File::open_read(file);
    return f.has_attribute("/", "format") ? f.attribute_string("/", "format") : std::string();
  };
  try {
    probe_in_child(file, [&] { read(); });
    return read();
  } catch (const Error&) {
    return "";
  }
}

}  // namespace

GcPlan plan_gc(const GcOptions& o) {
  GcPlan plan;
  const fs::path root = normal(o.results_dir);
  std::error_code ec;
  std::map<fs::path, const IndexedRun*> by_file;
  RunScan scan;
  if (fs::is_directory(root, ec)) {
    scan = scan_runs({root}, runs_index_path(o.results_dir));
    for (const auto& r : scan.runs) by_file[r.file] = &r;
  }
  const Current current = current_outputs(o, candidate_profiles(o, scan));
  // Current results, then everything they name (upstream, outputs, dataset).
  std::set<fs::path> keep;
  std::set<std::string> keep_datasets = current.dataset_names;
  std::vector<const IndexedRun*> todo;
  std::set<fs::path> sweeps_kept;
  for (const auto& r : scan.runs) {
    const fs::path sweep = sweep_folder_of(r.file, root);
    bool current_sweep = false;
    if (!sweep.empty()) {
      try {
        current_sweep = current.names.count(load_plan(sweep).experiment) > 0;
      } catch (const Error&) {
        current_sweep = true;  // an unreadable plan: not judged
      }
    }
    if (current.hashes.count(r.summary.config_hash) || current_sweep) {
      if (current_sweep) sweeps_kept.insert(sweep);
      todo.push_back(&r);
    }
  }
  while (!todo.empty()) {
    const IndexedRun* r = todo.back();
    todo.pop_back();
    if (!keep.insert(r->file).second) continue;
    if (!r->summary.dataset_file.empty())
      keep_datasets.insert(fs::path(r->summary.dataset_file).filename().string());
    std::vector<fs::path> named;
    for (const auto& u : r->summary.upstream_files) named.push_back(normal(u));
    for (const auto& out : r->summary.output_files) {
      named.push_back((r->file.parent_path() / out).lexically_normal());
    }
    for (const auto& p : named) {
      keep.insert(p);
      const fs::path sweep = sweep_folder_of(p, root);
      if (!sweep.empty()) sweeps_kept.insert(sweep);
      const auto it = by_file.find(p);
      if (it != by_file.end()) todo.push_back(it->second);
    }
  }
  // Results: stale ones with their outputs; sweep folders as one item.
  std::set<fs::path> stale_sweeps;
  for (const auto& r : scan.runs) {
    const fs::path sweep = sweep_folder_of(r.file, root);
    if (!sweep.empty() && sweeps_kept.count(sweep) == 0) {
      stale_sweeps.insert(sweep);
      continue;
    }
    if (!sweep.empty()) continue;  // inside a kept sweep folder
    if (keep.count(r.file)) {
      ++plan.kept;
      continue;
    }
    plan.stale.push_back({r.file, r.size, "result"});
    for (const auto& out : r.summary.output_files) {
      const fs::path p = (r.file.parent_path() / out).lexically_normal();
      // Kept, gone, or in a sweep folder (judged with its folder): not here.
      if (keep.count(p) || !fs::is_regular_file(p, ec) || !sweep_folder_of(p, root).empty())
        continue;
      plan.stale.push_back({p, size_of(p), "job output"});
    }
  }
  for (const auto& s : stale_sweeps) plan.stale.push_back({s, size_of(s), "sweep folder"});
  plan.kept += sweeps_kept.size();
  plan.foreign += scan.unreadable.size();
  // Datasets: cache files no current run reads.
  if (fs::is_directory(o.datasets_dir, ec)) {
    for (const auto& e : fs::directory_iterator(o.datasets_dir, ec)) {
      const fs::path& p = e.path();
      if (!e.is_regular_file(ec) || p.extension() != ".h5" || is_partial_path(p)) continue;
      if (keep_datasets.count(p.filename().string())) {
        ++plan.kept;
      } else if (hdf5_format(p) == kDatasetFormat) {
        plan.stale.push_back({normal(p), e.file_size(ec), "dataset"});
      } else {
        ++plan.foreign;
      }
    }
  }
  // The stage cache (experiment/narx_stage_cache.hpp) is only ever a cache:
  // it holds stages of every program that trained, so it is always listed.
  const fs::path stages = o.datasets_dir / "narx-stages";
  if (fs::is_directory(stages, ec)) {
    plan.stale.push_back({normal(stages), size_of(stages), "stage cache"});
  }
  std::sort(plan.stale.begin(), plan.stale.end(),
            [](const GcItem& a, const GcItem& b) { return a.path < b.path; });
  plan.stale.erase(std::unique(plan.stale.begin(), plan.stale.end(),
                               [](const GcItem& a, const GcItem& b) { return a.path == b.path; }),
                   plan.stale.end());
  return plan;
}

namespace {
std::string bytes_text(std::uintmax_t b) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB"};
  double v = static_cast<double>(b);
  int u = 0;
  while (v >= 1000 && u < 4) {
    v /= 1000;
    ++u;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.1f %s", v, units[u]);
  return buf;
}
}  // namespace

int gc_command(const GcOptions& o, std::ostream& out) {
  const GcPlan plan = plan_gc(o);
  std::uintmax_t total = 0;
  for (const auto& item : plan.stale) {
    out << (o.remove ? "removing  " : "stale     ") << bytes_text(item.bytes) << "\t" << item.what
        << "\t" << item.path.string() << "\n";
    total += item.bytes;
    if (o.remove) {
      std::error_code ec;
      fs::remove_all(item.path, ec);
      if (ec) throw IoError(item.path.string() + ": cannot remove: " + ec.message());
    }
  }
  out << plan.stale.size() << " stale item" << (plan.stale.size() == 1 ? "" : "s") << ", "
      << bytes_text(total) << (o.remove ? " removed" : "") << "; " << plan.kept << " current kept";
  if (plan.foreign) out << ", " << plan.foreign << " other files not judged (left alone)";
  out << "\n";
  if (!o.remove && !plan.stale.empty()) out << "nothing removed (dry run); --yes removes them\n";
  return 0;
}

}  // namespace cnclab
