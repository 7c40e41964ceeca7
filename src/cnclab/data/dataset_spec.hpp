#pragma once
// A `dataset:` section, {generator, seed?, targets?, options: {...}}: what
// experiments, jobs and `cnclab dataset generate` read (generator.hpp).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/core/fields.hpp"
#include "cnclab/data/generator.hpp"

namespace cnclab {

// dataset: {generator, seed?, options: {...generator options...}}
struct DatasetSpec {
  // The named generator with its options read and validated
  // (data/generator.hpp); never null in a loaded experiment.
  std::shared_ptr<const DatasetGenerator> generator;
  // Generator seed; absent = derived from the experiment seed ("generator").
  std::optional<std::uint64_t> seed;
  // targets: [X] - the generator's targets the model learns, in this order;
  // empty = all. One network per output (seed 004 Table 5) selects one.
  std::vector<std::string> targets;
};

// dataset: {generator, seed?, targets?, options}; `generator` reads its
// `options` (their keys depend on it: GeneratorEntry::options).
const FieldList<DatasetSpec>& dataset_fields();

// Reads a `dataset` section (strict; `cnclab dataset generate` and experiments).
DatasetSpec read_dataset_spec(const ConfigReader& dataset_section);

}  // namespace cnclab
