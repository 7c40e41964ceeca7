#pragma once
// What a trainer returns: why it stopped and the per-epoch history.
// Non-convergence and divergence are results, not exceptions.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace cnclab {

enum class Termination {
  max_epochs,           // ran the configured number of epochs
  early_stop,           // validation loss stopped improving (best parameters restored)
  diverged,             // loss or parameters became NaN/Inf
  stopped_by_callback,  // an observer asked to stop
  goal,                 // LM: objective reached the goal
  min_gradient,         // LM: gradient norm fell below the minimum
  mu_max,               // LM: damping mu exceeded mu_max without a successful step
};
std::string to_string(Termination t);
// Inverse of to_string; false if `text` names no termination.
bool parse_termination(const std::string& text, Termination& t);

struct EpochRecord {
  std::size_t epoch = 0;       // 1-based
  double train_loss = 0;       // mean mini-batch loss over the epoch (training mode); LM: SSE / N
  double validation_loss = 0;  // NaN when there is no validation set
  double wall_seconds = 0;     // since training started
};

// One Levenberg-Marquardt epoch (lm and trainbr), at the end of the epoch:
// the state the next step starts from.
struct LmEpochRecord {
  double sse = 0;       // E_D = sum of squared residuals
  double ssw = 0;       // E_W = sum of squared parameters
  double alpha = 0;     // weight-decay coefficient (lm: 0)
  double beta = 1;      // data coefficient (lm: 1)
  double gamma = 0;     // effective number of parameters (lm: N_w)
  double mu = 0;        // damping after the epoch's accepted step
  double gradient = 0;  // 2 ||J^T e||, the data-term gradient norm
  // beta max_i (J^T J)_ii: the curvature scale mu competes with. While mu is
  // far below it, the step is Gauss-Newton's in the stiff directions;
  // mu_max below it means the step never becomes a short gradient step.
  double curvature = 0;
};

struct Summary {
  Termination termination = Termination::max_epochs;
  std::string message;
  std::vector<EpochRecord> history;
  std::size_t best_epoch = 0;  // epoch of the lowest validation loss (0: none)
  // lm / trainbr only: one record per entry of `history`, and the state
  // before the first step (mu: the initial damping), which a run that stops
  // without a step has only.
  std::vector<LmEpochRecord> lm_history;
  std::optional<LmEpochRecord> lm_initial;
  // trainbr only: epochs in which beta = (N - gamma) / (2 E_D) was not
  // positive and the previous beta was kept.
  std::size_t beta_guard_count = 0;
};

}  // namespace cnclab
