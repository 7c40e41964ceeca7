#pragma once
// What a trainer returns: why it stopped and the per-epoch history.
// Non-convergence and divergence are results, not exceptions.
#include <cstddef>
#include <string>
#include <vector>

namespace cnclab {

enum class Termination {
  max_epochs,           // ran the configured number of epochs
  early_stop,           // validation loss stopped improving (best parameters restored)
  diverged,             // loss or parameters became NaN/Inf
  stopped_by_callback,  // an observer asked to stop
};
std::string to_string(Termination t);

struct EpochRecord {
  std::size_t epoch = 0;       // 1-based
  double train_loss = 0;       // mean mini-batch loss over the epoch (training mode)
  double validation_loss = 0;  // NaN when there is no validation set
  double wall_seconds = 0;     // since training started
};

struct Summary {
  Termination termination = Termination::max_epochs;
  std::string message;
  std::vector<EpochRecord> history;
  std::size_t best_epoch = 0;  // epoch of the lowest validation loss (0: none)
};

}  // namespace cnclab
