#include "cnclab/experiment/result_store.hpp"

#include "cnclab/core/hash.hpp"
#include "cnclab/experiment/result_file.hpp"

namespace cnclab {
namespace fs = std::filesystem;

ResultKey result_key(const LoadedExperiment& experiment) {
  const ExperimentSpec& spec = experiment.spec;
  return {spec.name, spec.seed, experiment.resolved_yaml, spec.source_file,
          !upstream_files(spec).empty()};
}

fs::path result_path(const ResultKey& key, const fs::path& results_dir) {
  const std::string seed = key.seed ? "-seed" + std::to_string(*key.seed) : "";
  const std::string hash = hash_hex(key.resolved_yaml).substr(0, 8);
  return results_dir / key.name / (key.name + seed + "-" + hash + ".h5");
}

fs::path result_path(const LoadedExperiment& experiment, const fs::path& results_dir) {
  return result_path(result_key(experiment), results_dir);
}

ResultStore::ResultStore(fs::path results_dir, std::string profile)
    : results_dir_(std::move(results_dir)), profile_(std::move(profile)) {}

fs::path ResultStore::path_of(const ResultKey& key) const {
  return result_path(key, results_dir_);
}

std::string ResultStore::make_command(const ResultKey& key) const {
  std::string command = std::string("cnclab ") + (key.has_upstream ? "reproduce " : "run ") +
                        key.source_file.lexically_normal().string();
  if (!profile_.empty()) command += " --profile " + profile_;
  const fs::path root = results_root(results_dir_, profile_);
  if (root != fs::path("results")) command += " --out " + root.string();
  return command;
}

LoadedExperiment ResultStore::load(const fs::path& experiment_file) const {
  return load_experiment(experiment_file, std::vector<std::string>{}, std::nullopt, profile_);
}

std::string ResultStore::missing_text(const ResultKey& key, const std::string& why) const {
  return "no result for " + key.source_file.lexically_normal().string() +
         (profile_.empty() ? "" : " (profile " + profile_ + ")") + ": " + why + "; make it with `" +
         make_command(key) + "`";
}

StoredResult ResultStore::checked(const ResultKey& key, StoredResult r) const {
  // A training result of format 1 has the test split's metrics only, not the
  // per-split ones selections need (result_file.hpp): made again, not reused.
  if (r.record.kind == "train" && r.record.format_version < kResultFormatVersion) {
    throw OutdatedResult(r.file.string() + ": result format " +
                         std::to_string(r.record.format_version) +
                         " (written before metrics per split; `cnclab show` still reads it): not "
                         "reused, run it again");
  }
  // The file name holds 8 hex digits of the identity; the file the full hash.
  if (r.record.config_hash != hash_hex(key.resolved_yaml)) {
    throw IoError(r.file.string() + ": config_hash " + r.record.config_hash +
                  " is not the hash of this resolved config (" + hash_hex(key.resolved_yaml) +
                  "): the result of another config");
  }
  return r;
}

std::optional<StoredResult> ResultStore::existing(const ResultKey& key) const {
  const fs::path file = path_of(key);
  std::error_code ec;
  if (!fs::exists(file, ec)) return std::nullopt;
  return checked(key, {file, read_result(file)});  // IoError unless complete and readable
}

StoredResult ResultStore::accepted(const ResultKey& key,
                                   const std::function<std::optional<StoredResult>()>& existing,
                                   Accept accept) const {
  std::optional<StoredResult> r;
  try {
    r = existing();
  } catch (const IoError& e) {
    throw MissingResults(missing_text(key, "no complete result (" + std::string(e.what()) + ")"));
  }
  if (!r) throw MissingResults(missing_text(key, "expected " + path_of(key).string()));
  if (accept == Accept::complete && !r->complete()) {
    throw Error(r->file.string() + ": the run failed (" + r->record.provenance.failure_reason +
                ")");
  }
  return std::move(*r);
}

StoredResult ResultStore::get(const ResultKey& key, Accept accept) const {
  return accepted(
      key, [&] { return existing(key); }, accept);
}

StoredResult ResultStore::get(const LoadedExperiment& experiment, Accept accept) const {
  return get(result_key(experiment), accept);
}

ResultKey ResultStore::key_of(const fs::path& experiment_file) const {
  std::error_code ec;
  if (!fs::exists(experiment_file, ec)) {
    throw MissingResults(experiment_file.string() + ": experiment file not found");
  }
  return result_key(load(experiment_file));
}

StoredResult ResultStore::get(const fs::path& experiment_file, Accept accept) const {
  return get(key_of(experiment_file), accept);
}

std::vector<StoredResult> ResultStore::get_all(const std::vector<fs::path>& experiment_files,
                                               Accept accept) const {
  std::vector<ResultKey> keys;
  std::vector<fs::path> files;  // the keys' result files that exist
  for (const auto& experiment_file : experiment_files) {
    keys.push_back(key_of(experiment_file));
    std::error_code ec;
    if (fs::exists(path_of(keys.back()), ec)) files.push_back(path_of(keys.back()));
  }
  std::vector<ReadOutcome<RunRecord>> read = read_results(files);
  std::vector<StoredResult> out;
  std::size_t k = 0;
  for (const auto& key : keys) {
    const bool exists = k < files.size() && files[k] == path_of(key);
    out.push_back(accepted(
        key,
        [&]() -> std::optional<StoredResult> {
          if (!exists) return std::nullopt;
          return checked(key, {files[k], std::move(read[k]).get()});
        },
        accept));
    k += exists;
  }
  return out;
}

std::string source_path_text(const fs::path& file) {
  if (file.is_relative()) return file.lexically_normal().string();
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (ec) return file.string();
  const fs::path rel = file.lexically_normal().lexically_relative(cwd);
  if (rel.empty() || *rel.begin() == "..") return file.string();
  return rel.string();
}

namespace {

// A folder of `root` with a result file (*.h5) or a sweep folder (sweep-*):
// results written to root directly.
bool results_folder_holds_results(const fs::path& root) {
  std::error_code ec;
  for (const auto& sub : fs::directory_iterator(root, ec)) {
    if (!sub.is_directory(ec)) continue;
    for (const auto& e : fs::directory_iterator(sub.path(), ec)) {
      const std::string name = e.path().filename().string();
      if (e.path().extension() == ".h5" || name.rfind("sweep-", 0) == 0) return true;
    }
  }
  return false;
}

}  // namespace

ResultsFolder results_folder(const fs::path& root, const std::string& profile, bool root_given) {
  if (profile.empty()) return {root, ""};
  const fs::path sub = root / profile;
  std::error_code ec;
  if (!root_given || fs::exists(sub, ec) || !results_folder_holds_results(root)) return {sub, ""};
  return {root, root.string() + " holds results directly and has no " + profile +
                    "/ folder: the layout `--out " + root.string() + " --profile " + profile +
                    "` wrote before results went to ROOT/PROFILE; using " + root.string() +
                    " as it is (move its contents into " + sub.string() +
                    " to use the new layout)"};
}

fs::path results_root(const fs::path& folder, const std::string& profile) {
  fs::path root = folder.lexically_normal();
  if (!profile.empty() && root.filename() == profile) {
    root = root.parent_path().empty() ? fs::path(".") : root.parent_path();
  }
  return root;
}

}  // namespace cnclab
