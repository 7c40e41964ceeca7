#include "cnclab/data/dataset_cache.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/constant_targets.hpp"
#include "cnclab/data/dataset_file.hpp"
#include "cnclab/io/lock_file.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// The cached dataset at `path` if it is readable and made by this generator
// config; nothing otherwise (with a note why).
bool read_cached(CachedDataset& out, const DatasetGenerator& generator,
                 const std::string& config_text, std::ostream* log) {
  std::error_code ec;
  if (!fs::exists(out.path, ec)) return false;
  try {
    Dataset cached = read_dataset(out.path);
    if (cached.generator == generator.name() && cached.generator_config == config_text) {
      out.dataset = std::move(cached);
      out.content_hash = out.dataset.content_hash();
      out.reused = true;
      return true;
    }
    if (log) *log << "note: " << out.path.string() << " holds another dataset; regenerating\n";
  } catch (const IoError& e) {
    if (log) *log << "note: cached dataset unusable (" << e.what() << "); regenerating\n";
  }
  return false;
}

}  // namespace

Dataset generate_dataset(const DatasetSpec& spec, std::uint64_t seed,
                         const ProgressCallback& progress) {
  Rng rng(seed);
  return spec.generator->generate(rng, progress);
}

// The cache key's text; a generator that ignores its seed gets none, so every
// seed shares one cached dataset (not identical data cached once per seed).
std::string dataset_config_text(const DatasetGenerator& generator, std::uint64_t seed) {
  return generator.options_yaml() + "generator_version: " + std::to_string(generator.version()) +
         "\n" + (generator.uses_seed() ? "seed: " + std::to_string(seed) + "\n" : "");
}

fs::path dataset_cache_file(const DatasetSpec& spec, std::uint64_t seed, const fs::path& dir) {
  const DatasetGenerator& generator = *spec.generator;
  const std::string key = Hasher()
                              .add(generator.name())
                              .add(std::string_view("\n"))
                              .add(dataset_config_text(generator, seed))
                              .hex();
  return dir / (generator.name() + "-" + key + ".h5");
}

CachedDataset obtain_dataset(const DatasetSpec& spec, std::uint64_t seed, const fs::path& dir,
                             std::ostream* log, bool regenerate, const ProgressCallback& progress) {
  // The key must not require generating. The generator's options, version
  // and seed are also stored in the dataset file, so the file says how to
  // make it again.
  const DatasetGenerator& generator = *spec.generator;
  const std::string config_text = dataset_config_text(generator, seed);
  CachedDataset out;
  out.path = dataset_cache_file(spec, seed, dir);
  const std::string stem = out.path.stem().string();

  // Unlocked first: a cache hit (the common case) costs no lock.
  if (!regenerate && read_cached(out, generator, config_text, nullptr)) return out;
  const LockFile lock(dir / ("." + stem + ".lock"), log);
  if (!regenerate && read_cached(out, generator, config_text, log)) return out;
  out.dataset = generate_dataset(spec, seed, progress);
  if (log) {
    for (const auto& t : constant_targets(out.dataset, generator.target_resolution())) {
      *log << "warning: dataset " << out.path.filename().string() << ": " << constant_target_text(t)
           << "\n";
    }
  }
  out.dataset.generator_config = config_text;
  out.content_hash = out.dataset.content_hash();
  write_dataset(out.path, out.dataset);
  return out;
}

}  // namespace cnclab
