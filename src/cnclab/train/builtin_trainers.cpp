// The trainers of `trainer.type`, one line each (trainer_registry.hpp); the
// first is the default type.
#include "cnclab/train/adam.hpp"
#include "cnclab/train/lm.hpp"
#include "cnclab/train/sgdm.hpp"
#include "cnclab/train/trainbr.hpp"
#include "cnclab/train/trainer_registry.hpp"

namespace cnclab {
namespace {

TrainerRegistry builtin_trainer_registry() {
  TrainerRegistry registry;
  registry.add(sgdm_trainer());
  registry.add(lm_trainer());
  registry.add(trainbr_trainer());
  registry.add(adam_trainer());
  return registry;
}

}  // namespace

const TrainerRegistry& trainers() {
  static const TrainerRegistry registry = builtin_trainer_registry();
  return registry;
}

}  // namespace cnclab
