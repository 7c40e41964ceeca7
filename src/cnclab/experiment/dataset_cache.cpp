#include "cnclab/experiment/dataset_cache.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/dataset_file.hpp"

namespace cnclab {
namespace fs = std::filesystem;

DatasetShape dataset_shape(const DatasetSpec& spec) {
  const auto& f = std::get<Friedman1Options>(spec.options);
  return {f.samples, f.inputs, 1};
}

Dataset generate_dataset(const DatasetSpec& spec, std::uint64_t seed) {
  Rng rng(seed);
  return std::visit([&](const auto& options) { return generate_friedman1(options, rng); },
                    spec.options);
}

CachedDataset obtain_dataset(const DatasetSpec& spec, std::uint64_t seed, const fs::path& dir,
                             std::ostream* log) {
  // The key must not require generating: use the generator's config text,
  // which generate_* also stores in the dataset.
  // The generator's options and its seed: stored in the dataset file, so the
  // file says how to make it again.
  const std::string config_text =
      std::visit([](const auto& o) { return generator_config_yaml(o); }, spec.options) +
      "seed: " + std::to_string(seed) + "\n";
  const std::string key =
      Hasher().add(spec.generator).add(std::string_view("\n")).add(config_text).add(seed).hex();
  CachedDataset out;
  out.path = dir / (spec.generator + "-" + key + ".h5");

  std::error_code ec;
  if (fs::exists(out.path, ec)) {
    try {
      Dataset cached = read_dataset(out.path);
      if (cached.generator == spec.generator && cached.generator_config == config_text) {
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
