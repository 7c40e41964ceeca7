#pragma once
// trainer: {type: sgdm | lm | trainbr, ...}: which trainer an experiment uses
// and its options. Keys per type (defaults in the options structs):
//   sgdm:       learning_rate, momentum, batch_size, epochs, shuffle, early_stop_patience,
//               precision
//   lm/trainbr: epochs, goal, mu, mu_dec, mu_inc, mu_max, min_gradient, form
// A key that only another type has (left from a fragment written for that
// type, e.g. after `trainer.type=trainbr` on an sgdm experiment) is dropped,
// with a note saying which; any other key of no type is an unknown key.
#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>
#include <variant>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/train/lm.hpp"
#include "cnclab/train/sgdm.hpp"
#include "cnclab/train/trainbr.hpp"

namespace cnclab {

using TrainerSpec = std::variant<SgdmOptions, LmOptions, TrainbrOptions>;

std::string trainer_name(const TrainerSpec& trainer);  // "sgdm", "lm" or "trainbr"
bool is_trainer_name(const std::string& name);
std::size_t trainer_epochs(const TrainerSpec& trainer);
// lm and trainbr need a deterministic objective (no dropout).
bool is_levenberg_marquardt(const TrainerSpec& trainer);

// Reads and validates the `trainer` section (`type` is required by the
// experiment reader; here it defaults to sgdm). Dropped keys of other types
// add one line to `notes` when given.
TrainerSpec read_trainer(const ConfigReader& r, std::vector<std::string>* notes = nullptr);
// The section with every option resolved, as a map.
YAML::Node trainer_to_node(const TrainerSpec& trainer);

}  // namespace cnclab
