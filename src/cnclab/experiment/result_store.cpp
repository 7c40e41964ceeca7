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
  // The CLI's default: results, or results/<profile> with a profile.
  const fs::path default_dir =
      profile_.empty() ? fs::path("results") : fs::path("results") / profile_;
  if (results_dir_.lexically_normal() != default_dir) command += " --out " + results_dir_.string();
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

std::optional<StoredResult> ResultStore::existing(const ResultKey& key) const {
  const fs::path file = path_of(key);
  std::error_code ec;
  if (!fs::exists(file, ec)) return std::nullopt;
  StoredResult r{file, read_result(file)};  // IoError unless complete and readable
  // The file name holds 8 hex digits of the identity; the file the full hash.
  if (r.record.config_hash != hash_hex(key.resolved_yaml)) {
    throw IoError(file.string() + ": config_hash " + r.record.config_hash +
                  " is not the hash of this resolved config (" + hash_hex(key.resolved_yaml) +
                  "): the result of another config");
  }
  return r;
}

StoredResult ResultStore::get(const ResultKey& key, Accept accept) const {
  std::optional<StoredResult> r;
  try {
    r = existing(key);
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

StoredResult ResultStore::get(const LoadedExperiment& experiment, Accept accept) const {
  return get(result_key(experiment), accept);
}

StoredResult ResultStore::get(const fs::path& experiment_file, Accept accept) const {
  std::error_code ec;
  if (!fs::exists(experiment_file, ec)) {
    throw MissingResults(experiment_file.string() + ": experiment file not found");
  }
  return get(load(experiment_file), accept);
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

}  // namespace cnclab
