#pragma once
// trainer: {type: <a registered trainer>, ...}: which trainer an experiment
// uses and its options. The types, their keys and defaults come from the
// trainer registry (train/trainer_registry.hpp; `cnclab schema` lists them).
// A key that only another type has (left from a fragment written for that
// type, e.g. after `trainer.type=B` on an experiment of type A) is dropped,
// with a note saying which; any other key of no type is an unknown key.
#include <yaml-cpp/yaml.h>

#include <any>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/train/trainer_registry.hpp"

namespace cnclab {

// A registered trainer and its options (the trainer's own options struct).
struct TrainerSpec {
  // The registry's first trainer (the default type) with its defaults.
  TrainerSpec();
  TrainerSpec(const TrainerDef& def, std::any options);

  const TrainerDef* def = nullptr;  // an entry of trainers()
  std::any options;
};

std::string trainer_name(const TrainerSpec& trainer);
std::size_t trainer_epochs(const TrainerSpec& trainer);
const TrainerCapabilities& trainer_capabilities(const TrainerSpec& trainer);

// The options when the trainer's options struct is O, else nullptr.
template <class O>
const O* trainer_options_if(const TrainerSpec& trainer) {
  return std::any_cast<O>(&trainer.options);
}
template <class O>
O* trainer_options_if(TrainerSpec& trainer) {
  return std::any_cast<O>(&trainer.options);
}
// The options as O; Error when they are another trainer's.
template <class O>
const O& trainer_options(const TrainerSpec& trainer) {
  if (const O* o = trainer_options_if<O>(trainer)) return *o;
  throw Error("trainer " + trainer_name(trainer) + " has other options");
}
template <class O>
O& trainer_options(TrainerSpec& trainer) {
  if (O* o = trainer_options_if<O>(trainer)) return *o;
  throw Error("trainer " + trainer_name(trainer) + " has other options");
}

// The registered trainers that pass `allowed` (all when empty).
using TrainerFilter = std::function<bool(const TrainerDef&)>;
std::vector<std::string> trainer_names(const TrainerFilter& allowed = {});

// Reads and validates the `trainer` section (`type` is required by the
// experiment reader; here it defaults to the first allowed trainer),
// allowing the trainers that pass `allowed`. Dropped keys of other types add
// one line to `notes` when given.
TrainerSpec read_trainer(const ConfigReader& r, std::vector<std::string>* notes = nullptr,
                         const TrainerFilter& allowed = {});
// The section with every option resolved, as a map.
YAML::Node trainer_to_node(const TrainerSpec& trainer);

}  // namespace cnclab
