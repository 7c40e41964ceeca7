#include "cnclab/train/adam.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/fields.hpp"

namespace cnclab {

const FieldList<AdamOptions>& adam_fields() {
  using O = AdamOptions;
  static const auto fields =
      FieldList<O>()
          .field("learning_rate", &O::learning_rate,
                 "lr: w ← w − lr/(1 − β1^t) · m/(√v/√(1 − β2^t) + eps) (torch.optim.Adam; "
                 "PyTorch: 1e-3)",
                 Rule::positive())
          .field("beta1", &O::beta1, "β1 ∈ [0, 1): m ← β1 m + (1 − β1) g (PyTorch: 0.9)",
                 Rule::in(0, true, 1, false))
          .field("beta2", &O::beta2, "β2 ∈ [0, 1): v ← β2 v + (1 − β2) g² (PyTorch: 0.999)",
                 Rule::in(0, true, 1, false))
          .field("eps", &O::eps, "added to the denominator (PyTorch: 1e-8)", Rule::positive())
          .field("weight_decay", &O::weight_decay,
                 "L2 coefficient: g ← g + weight_decay · w (PyTorch: 0)", Rule::non_negative())
          .field("amsgrad", &O::amsgrad,
                 "use the maximum of v so far in the denominator (PyTorch: false)")
          .field("batch_size", &O::batch_size, "samples per update", Rule::at_least(1))
          .field("epochs", &O::epochs,
                 "passes over the training split; 0 = evaluation only (parameters unchanged)")
          .field("shuffle", &O::shuffle, "new random sample order every epoch")
          .field("early_stop_patience", &O::early_stop_patience,
                 "stop after this many epochs without a lower validation loss, restoring the "
                 "best parameters (0 = off)");
  return fields;
}

void AdamOptions::validate() const {
  adam_fields().check(*this);
}

Summary train_adam(SeparableObjective& objective, Eigen::VectorXd& params,
                   const AdamOptions& options, Rng& shuffle_rng, const TrainingHooks& hooks) {
  options.validate();
  if (options.early_stop_patience > 0 && !hooks.validation_loss) {
    throw Error("adam: early_stop_patience > 0 needs a validation set");
  }
  if (static_cast<std::size_t>(params.size()) != objective.num_parameters()) {
    throw Error("adam: " + std::to_string(params.size()) + " parameters given, objective has " +
                std::to_string(objective.num_parameters()));
  }
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = objective.num_samples();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  const double beta1 = options.beta1, beta2 = options.beta2;
  Eigen::VectorXd m = Eigen::VectorXd::Zero(params.size());
  Eigen::VectorXd v = Eigen::VectorXd::Zero(params.size());
  Eigen::VectorXd v_max = Eigen::VectorXd::Zero(options.amsgrad ? params.size() : 0);
  Eigen::VectorXd gradient(params.size());
  Eigen::VectorXd best_params;
  double best_validation = std::numeric_limits<double>::infinity();
  double step = 0;  // t
  Summary summary;

  for (std::size_t epoch = 1; epoch <= options.epochs; ++epoch) {
    if (options.shuffle) shuffle_rng.shuffle(order);
    double loss_sum = 0;
    std::size_t batches = 0;
    for (std::size_t first = 0; first < n; first += options.batch_size) {
      const std::size_t count = std::min(options.batch_size, n - first);
      const std::span<const std::size_t> batch(order.data() + first, count);
      const double loss = objective.loss_and_gradient(params, batch, gradient);
      if (!std::isfinite(loss) || !gradient.allFinite()) {
        summary.termination = Termination::diverged;
        summary.message = "diverged: loss " + std::to_string(loss) + " in epoch " +
                          std::to_string(epoch) + ", batch " + std::to_string(batches + 1) +
                          " (try a smaller learning_rate)";
        return summary;
      }
      // torch.optim.Adam, in its order of operations (adam.hpp).
      step += 1;
      if (options.weight_decay != 0) gradient += options.weight_decay * params;
      m = m * beta1 + (1 - beta1) * gradient;
      v = v * beta2 + ((1 - beta2) * gradient).cwiseProduct(gradient);
      const double step_size = options.learning_rate / (1 - std::pow(beta1, step));
      const double correction2_sqrt = std::sqrt(1 - std::pow(beta2, step));
      if (options.amsgrad) v_max = v_max.cwiseMax(v);
      const Eigen::VectorXd& second = options.amsgrad ? v_max : v;
      params += ((-step_size) * m)
                    .cwiseQuotient(
                        ((second.cwiseSqrt() / correction2_sqrt).array() + options.eps).matrix());
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

TrainerDef adam_trainer() {
  TrainerCapabilities can;
  can.dropout = can.mini_batches = can.validation_stop = true;
  return make_trainer<AdamOptions>(
      "adam", "Adam with torch.optim.Adam's semantics", adam_fields(), can, TrainerHistory::epochs,
      [](const AdamOptions& options, const MlpTrainingProblem& p, Eigen::VectorXd& params) {
        Rng dropout_rng(p.seed, "dropout");
        Rng shuffle_rng(p.seed, "shuffle");
        MlpRegressionObjective objective(p.mlp, p.x, p.y, dropout_rng);
        return train_adam(objective, params, options, shuffle_rng, p.hooks);
      });
}

}  // namespace cnclab
