#pragma once
// Stochastic gradient descent with momentum, seed 000 Eq. (14):
//   v_{t+1} = beta v_t - eta dE/dw(t),   w(t+1) = w(t) + v_{t+1},   v_0 = 0,
// one update per mini-batch. (PyTorch's form v <- beta v + g, w <- w - eta v
// is the same sequence of weights for a constant eta.)
#include <Eigen/Core>
#include <cstddef>
#include <functional>

#include "cnclab/core/rng.hpp"
#include "cnclab/train/objective.hpp"
#include "cnclab/train/summary.hpp"

namespace cnclab {

template <class S>
class FieldList;
struct TrainerDef;

// The arithmetic of the training loop. float64 is the default and the
// reference; float32 keeps the weights, the momentum and every product of
// the forward and backward passes in float, as PyTorch trains by default
// (faster: twice the numbers per vector register and half the memory
// traffic). The returned weights are the float weights widened to double;
// validation losses and callbacks see those. Its distance from float64 over
// a whole run is bounded in tests/train/sgdm_test.cpp and docs/performance.md.
enum class Precision { float64, float32 };

struct SgdmOptions {
  double learning_rate = 1e-5;  // eta > 0 (seed 000: 1e-5)
  double momentum = 0.8;        // beta in [0, 1) (seed 000: 0.8)
  // Samples per update; 1 = seed 000's per-sample SGD. The last batch of an
  // epoch holds the remainder (n mod batch_size) and is used, not dropped.
  std::size_t batch_size = 1;
  // seed 000: 2000. 0 = no update at all: the parameters are returned
  // bit-identical (an evaluation-only run of a given network).
  std::size_t epochs = 2000;
  bool shuffle = true;  // new random sample order every epoch
  // Stop after this many epochs without a lower validation loss and restore
  // the best parameters; 0 = off. Needs a validation set.
  std::size_t early_stop_patience = 0;
  Precision precision = Precision::float64;  // arithmetic of the loop (above)

  void validate() const;
};

// The YAML fields of SgdmOptions (`trainer:` with type sgdm), declared once
// (core/fields.hpp); validate() checks their rules.
const FieldList<SgdmOptions>& sgdm_fields();

struct SgdmHooks {
  // Loss on held-out data at the end of each epoch (evaluation mode).
  std::function<double(const Eigen::VectorXd& params)> validation_loss;
  // Called after every epoch; returning false stops training.
  std::function<bool(const EpochRecord&, const Eigen::VectorXd& params)> on_epoch;
};

Summary train_sgdm(SeparableObjective& objective, Eigen::VectorXd& params,
                   const SgdmOptions& options, Rng& shuffle_rng, const SgdmHooks& hooks = {});

// `trainer.type: sgdm` (trainer_registry.hpp): an MLP with dropout masks from
// Rng(seed, "dropout") and the sample order from Rng(seed, "shuffle").
TrainerDef sgdm_trainer();

}  // namespace cnclab
