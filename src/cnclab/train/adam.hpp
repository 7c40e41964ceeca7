#pragma once
// Adam (Kingma & Ba 2015) with torch.optim.Adam's semantics (PyTorch 1.13,
// the single-tensor path), one update per mini-batch, t = 1, 2, ...:
//   g <- g + weight_decay w                       (L2 penalty in the gradient)
//   m <- beta1 m + (1 - beta1) g
//   v <- beta2 v + (1 - beta2) g*g
//   v_max <- max(v_max, v)   (amsgrad; then v_max replaces v below)
//   w <- w - (lr / (1 - beta1^t)) m / (sqrt(v) / sqrt(1 - beta2^t) + eps)
// with m = v = v_max = 0 at the start. Mini-batches, shuffling, dropout,
// validation and early stop as SGDM (sgdm.hpp).
#include <Eigen/Core>
#include <cstddef>

#include "cnclab/core/rng.hpp"
#include "cnclab/train/objective.hpp"
#include "cnclab/train/summary.hpp"
#include "cnclab/train/trainer_registry.hpp"

namespace cnclab {

struct AdamOptions {
  double learning_rate = 1e-3;  // lr > 0 (PyTorch: 1e-3)
  double beta1 = 0.9;           // first-moment decay in [0, 1) (PyTorch: 0.9)
  double beta2 = 0.999;         // second-moment decay in [0, 1) (PyTorch: 0.999)
  double eps = 1e-8;            // added to the denominator, > 0 (PyTorch: 1e-8)
  double weight_decay = 0;      // L2 coefficient added to the gradient, >= 0 (PyTorch: 0)
  bool amsgrad = false;         // the maximum of v so far in the denominator (PyTorch: false)
  // Samples per update; the last batch of an epoch holds the remainder.
  // PyTorch has no default (its DataLoader's is 1); 32 is the common choice.
  std::size_t batch_size = 32;
  std::size_t epochs = 100;  // 0 = no update (parameters returned bit-identical)
  bool shuffle = true;       // new random sample order every epoch
  // Stop after this many epochs without a lower validation loss and restore
  // the best parameters; 0 = off. Needs a validation set.
  std::size_t early_stop_patience = 0;

  void validate() const;
};

// The YAML fields of AdamOptions (`trainer:` with type adam), declared once.
const FieldList<AdamOptions>& adam_fields();

Summary train_adam(SeparableObjective& objective, Eigen::VectorXd& params,
                   const AdamOptions& options, Rng& shuffle_rng, const TrainingHooks& hooks = {});

// `trainer.type: adam`: an MLP with dropout masks from Rng(seed, "dropout")
// and the sample order from Rng(seed, "shuffle"), as sgdm.
TrainerDef adam_trainer();

}  // namespace cnclab
