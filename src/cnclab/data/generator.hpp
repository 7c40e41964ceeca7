#pragma once
// Dataset generators behind one interface, and the registry that maps an
// experiment's `dataset.generator` name to the code that reads its
// `dataset.options`. Adding a generator: implement DatasetGenerator in its
// own file with a reader function, and list the reader in
// builtin_generators() (generator.cpp).
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/core/field_info.hpp"
#include "cnclab/core/progress.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/dataset.hpp"

namespace cnclab {

struct DatasetShape {
  std::size_t samples = 0, inputs = 0, outputs = 0;
};

// A generator with its options read and validated: immutable, shareable.
class DatasetGenerator {
 public:
  virtual ~DatasetGenerator() = default;
  // The registry name, e.g. "friedman1"; stored in every dataset it makes.
  virtual std::string name() const = 0;
  // Raised whenever the generator's output changes for the same options and
  // seed: part of the dataset cache key, so an old cached file is never
  // mistaken for the new generator's output.
  virtual int version() const = 0;
  // The shape generate() will produce, known without generating (memory
  // checks before any work).
  virtual DatasetShape shape() const = 0;
  // The resolved options, defaults included, as a YAML block map whose
  // numbers read back exactly (core/format.hpp). Printed by `cnclab
  // validate`, stored in the dataset, hashed into the cache key.
  virtual std::string options_yaml() const = 0;
  // Makes the dataset; all randomness comes from `rng` (deterministic
  // generators ignore it). Sets Dataset::generator; the caller sets
  // generator_config.
  virtual Dataset generate(Rng& rng) const = 0;
  // The same, reporting progress (core/progress.hpp) where generation takes
  // long enough to need it; by default it reports nothing.
  virtual Dataset generate(Rng& rng, const ProgressCallback& /*progress*/) const {
    return generate(rng);
  }
  // False for a deterministic generator: its seed is then left out of the
  // dataset cache key, so runs with other seeds share one cached file.
  virtual bool uses_seed() const { return true; }
  // Per target, in the target's unit: the spread below which the values are
  // numerical noise of the computation, not data (constant_targets.hpp).
  // Empty (the default): no such floor is known.
  virtual std::vector<double> target_resolution() const { return {}; }
};

// Reads a generator's options from its config section; strict (unknown keys
// and bad values are ConfigErrors naming the file position).
using GeneratorReader =
    std::function<std::shared_ptr<const DatasetGenerator>(const ConfigReader& options)>;

struct GeneratorEntry {
  std::string name;
  std::string summary;  // one line: what the generator makes
  GeneratorReader read;
  // The declared `options` keys (core/fields.hpp) for `cnclab schema`; empty
  // while a generator's options are not declared yet.
  std::function<std::vector<FieldInfo>()> options = {};
};

// The built-in generators in a fixed order; a new list each call (no global
// registry to mutate).
std::vector<GeneratorEntry> builtin_generators();

// Reads `dataset.generator` (default friedman1) and `dataset.options` from a
// `dataset` section; an unknown name is a ConfigError listing the known ones.
std::shared_ptr<const DatasetGenerator> read_generator(const ConfigReader& dataset_section);

}  // namespace cnclab
