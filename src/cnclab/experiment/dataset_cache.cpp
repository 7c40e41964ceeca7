#include "cnclab/experiment/dataset_cache.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/dataset_file.hpp"

namespace cnclab {
namespace fs = std::filesystem;

Dataset generate_dataset(const DatasetSpec& spec, std::uint64_t seed) {
  Rng rng(seed);
  return spec.generator->generate(rng);
}

std::string dataset_config_text(const DatasetGenerator& generator, std::uint64_t seed) {
  return generator.options_yaml() + "generator_version: " + std::to_string(generator.version()) +
         "\nseed: " + std::to_string(seed) + "\n";
}

CachedDataset obtain_dataset(const DatasetSpec& spec, std::uint64_t seed, const fs::path& dir,
                             std::ostream* log) {
  // The key must not require generating. The generator's options, version
  // and seed are also stored in the dataset file, so the file says how to
  // make it again.
  const DatasetGenerator& generator = *spec.generator;
  const std::string config_text = dataset_config_text(generator, seed);
  const std::string key =
      Hasher().add(generator.name()).add(std::string_view("\n")).add(config_text).hex();
  CachedDataset out;
  out.path = dir / (generator.name() + "-" + key + ".h5");

  std::error_code ec;
  if (fs::exists(out.path, ec)) {
    try {
      Dataset cached = read_dataset(out.path);
      if (cached.generator == generator.name() && cached.generator_config == config_text) {
        out.dataset = std::move(cached);
        out.content_hash = out.dataset.content_hash();
        out.reused = true;
        return out;
      }
      if (log) *log << "note: " << out.path.string() << " holds another dataset; regenerating\n";
    } catch (const IoError& e) {
      if (log) *log << "note: cached dataset unusable (" << e.what() << "); regenerating\n";
    }
  }
  out.dataset = generate_dataset(spec, seed);
  out.dataset.generator_config = config_text;
  out.content_hash = out.dataset.content_hash();
  write_dataset(out.path, out.dataset);
  return out;
}

}  // namespace cnclab
