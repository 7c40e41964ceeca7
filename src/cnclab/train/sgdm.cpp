#include "cnclab/train/sgdm.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/fields.hpp"

namespace cnclab {

const FieldList<SgdmOptions>& sgdm_fields() {
  using O = SgdmOptions;
  static const auto fields =
      FieldList<O>()
          .field("learning_rate", &O::learning_rate,
                 "η: v ← βv − η∇E, w ← w + v (seed 000 Eq. 14; seed 000: 1e-5)", Rule::positive())
          .field("momentum", &O::momentum, "β ∈ [0, 1) (seed 000: 0.8)",
                 Rule::in(0, true, 1, false))
          .field("batch_size", &O::batch_size,
                 "samples per update; 1 = per-sample SGD as in seed 000", Rule::at_least(1))
          .field("epochs", &O::epochs,
                 "passes over the training split; 0 = evaluation only (parameters unchanged)")
          .field("shuffle", &O::shuffle, "new random sample order every epoch")
          .field("early_stop_patience", &O::early_stop_patience,
                 "stop after this many epochs without a lower validation loss, restoring the "
                 "best parameters (0 = off)");
  return fields;
}

void SgdmOptions::validate() const {
  sgdm_fields().check(*this);
}

Summary train_sgdm(SeparableObjective& objective, Eigen::VectorXd& params,
                   const SgdmOptions& options, Rng& shuffle_rng, const SgdmHooks& hooks) {
  options.validate();
  if (options.early_stop_patience > 0 && !hooks.validation_loss) {
    throw Error("sgdm: early_stop_patience > 0 needs a validation set");
  }
  if (static_cast<std::size_t>(params.size()) != objective.num_parameters()) {
    throw Error("sgdm: " + std::to_string(params.size()) + " parameters given, objective has " +
                std::to_string(objective.num_parameters()));
  }
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = objective.num_samples();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  Eigen::VectorXd velocity = Eigen::VectorXd::Zero(params.size());
  Eigen::VectorXd gradient(params.size());
  Eigen::VectorXd best_params;
  double best_validation = std::numeric_limits<double>::infinity();
  Summary summary;

  for (std::size_t epoch = 1; epoch <= options.epochs; ++epoch) {
    if (options.shuffle) shuffle_rng.shuffle(order);
    double loss_sum = 0;
    std::size_t batches = 0;
    for (std::size_t first = 0; first < n; first += options.batch_size) {
      const std::size_t count = std::min(options.batch_size, n - first);
      const double loss = objective.loss_and_gradient(
          params, std::span<const std::size_t>(order.data() + first, count), gradient);
      if (!std::isfinite(loss) || !gradient.allFinite()) {
        summary.termination = Termination::diverged;
        summary.message = "diverged: loss " + std::to_string(loss) + " in epoch " +
                          std::to_string(epoch) + ", batch " + std::to_string(batches + 1) +
                          " (try a smaller learning_rate)";
        return summary;
      }
      velocity = options.momentum * velocity - options.learning_rate * gradient;  // Eq. (14)
      params += velocity;
      loss_sum += loss;
      ++batches;
    }
    EpochRecord record;
    record.epoch = epoch;
    record.train_loss = batches ? loss_sum / static_cast<double>(batches) : std::nan("");
    record.validation_loss = hooks.validation_loss ? hooks.validation_loss(params) : std::nan("");
    record.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary.history.push_back(record);
    if (!params.allFinite()) {
      summary.termination = Termination::diverged;
      summary.message = "diverged: parameters not finite after epoch " + std::to_string(epoch);
      return summary;
    }
    if (hooks.on_epoch && !hooks.on_epoch(record, params)) {
      summary.termination = Termination::stopped_by_callback;
      summary.message = "stopped by callback after epoch " + std::to_string(epoch);
      return summary;
    }
    if (hooks.validation_loss && record.validation_loss < best_validation) {
      best_validation = record.validation_loss;
      summary.best_epoch = epoch;
      if (options.early_stop_patience > 0) best_params = params;
    }
    if (options.early_stop_patience > 0 &&
        epoch - summary.best_epoch >= options.early_stop_patience) {
      if (best_params.size() == params.size()) params = best_params;
      summary.termination = Termination::early_stop;
      summary.message = "early stop: no validation improvement for " +
                        std::to_string(options.early_stop_patience) + " epochs; restored epoch " +
                        std::to_string(summary.best_epoch);
      return summary;
    }
  }
  summary.termination = Termination::max_epochs;
  summary.message = "completed " + std::to_string(options.epochs) + " epochs";
  return summary;
}

}  // namespace cnclab
