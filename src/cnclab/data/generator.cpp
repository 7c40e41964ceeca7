#include "cnclab/data/generator.hpp"

#include <stdexcept>
#include <utility>

#include "cnclab/core/suggest.hpp"
#include "cnclab/data/following_error.hpp"
#include "cnclab/data/friedman1.hpp"
#include "cnclab/data/generator_registry.hpp"
#include "cnclab/data/ik_samples.hpp"
#include "cnclab/data/step_error.hpp"

namespace cnclab {
namespace {

// The generators studies registered (register_generator), in order.
std::vector<GeneratorEntry>& registered_generators() {
  static std::vector<GeneratorEntry> entries;
  return entries;
}

}  // namespace

std::vector<GeneratorEntry> builtin_generators() {
  return {
      {"friedman1", "Friedman #1 regression benchmark (noisy, d >= 5 inputs)", read_friedman1,
       [] { return friedman1_fields().info(); }},
      {"step_error",
       "step errors of an iso-parametric ball-end tool path on a NURBS surface (seed 000)",
       read_step_error, [] { return step_error_fields().info(); }},
      {"ik_samples",
       "TTTRR five-axis inverse kinematics: tool poses -> joints X, Y, Z, A, C (seed 004)",
       read_ik_samples, [] { return ik_samples_fields().info(); }},
      {"following_error",
       "axis following errors of a simulated biaxial machine on a random NURBS path: reference "
       "velocity -> following error per axis, 10 runs averaged, csaps-smoothed (seed 002)",
       read_following_error, [] { return following_error_fields().info(); }},
  };
}

void register_generator(GeneratorEntry entry) {
  for (const auto& known : known_generators()) {
    if (known.name == entry.name) {
      throw std::logic_error("dataset generator '" + entry.name + "' registered twice");
    }
  }
  registered_generators().push_back(std::move(entry));
}

std::vector<GeneratorEntry> known_generators() {
  std::vector<GeneratorEntry> all = builtin_generators();
  all.insert(all.end(), registered_generators().begin(), registered_generators().end());
  return all;
}

std::shared_ptr<const DatasetGenerator> read_generator(const ConfigReader& dataset_section) {
  std::string known;
  std::vector<std::string> names;
  const std::vector<GeneratorEntry> generators = known_generators();
  for (const auto& entry : generators) {
    known += (known.empty() ? "" : ", ") + entry.name;
    names.push_back(entry.name);
  }
  // No default generator: a dataset block that forgets it must not silently
  // become some built-in benchmark.
  if (!dataset_section.has("generator")) {
    dataset_section.fail("generator", "is required (one of: " + known + ")");
  }
  const auto name = dataset_section.require<std::string>("generator");
  for (const auto& entry : generators) {
    if (entry.name == name) return entry.read(dataset_section.section("options"));
  }
  dataset_section.fail("generator", "must be one of: " + known + did_you_mean(name, names));
}

}  // namespace cnclab
