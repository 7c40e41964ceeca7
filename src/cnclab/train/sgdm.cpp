#include "cnclab/train/sgdm.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <type_traits>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/fields.hpp"
#include "cnclab/train/trainer_registry.hpp"

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
                 "best parameters (0 = off)")
          .choice("precision", &O::precision,
                  {{"float64", Precision::float64}, {"float32", Precision::float32}},
                  "arithmetic of training: float64 (default, the reference) or float32 (as "
                  "PyTorch; faster, agrees with float64 to the bound in docs/performance.md)");
  return fields;
}

void SgdmOptions::validate() const {
  sgdm_fields().check(*this);
}

namespace {

// The loop of train_sgdm in T (double or float); `params` is the double
// vector callers see, `w` the weights the loop updates (params itself for
// double; for float, params is refreshed from w whenever someone looks).
template <class T>
Summary sgdm_loop(SeparableObjective& objective, Eigen::VectorXd& params,
                  Eigen::Matrix<T, Eigen::Dynamic, 1>& w, const SgdmOptions& options,
                  Rng& shuffle_rng, const SgdmHooks& hooks) {
  using Vector = Eigen::Matrix<T, Eigen::Dynamic, 1>;
  constexpr bool kDouble = std::is_same_v<T, double>;
  const auto publish = [&] {
    if constexpr (!kDouble) params = w.template cast<double>();
  };
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = objective.num_samples();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  const T momentum = static_cast<T>(options.momentum);
  const T learning_rate = static_cast<T>(options.learning_rate);
  Vector velocity = Vector::Zero(w.size());
  Vector gradient(w.size());
  Vector best_params;
  double best_validation = std::numeric_limits<double>::infinity();
  Summary summary;

  for (std::size_t epoch = 1; epoch <= options.epochs; ++epoch) {
    if (options.shuffle) shuffle_rng.shuffle(order);
    double loss_sum = 0;
    std::size_t batches = 0;
    for (std::size_t first = 0; first < n; first += options.batch_size) {
      const std::size_t count = std::min(options.batch_size, n - first);
      const std::span<const std::size_t> batch(order.data() + first, count);
      double loss = 0;
      if constexpr (kDouble) {
        loss = objective.loss_and_gradient(w, batch, gradient);
      } else {
        loss = objective.loss_and_gradient_float32(w, batch, gradient);
      }
      if (!std::isfinite(loss) || !gradient.allFinite()) {
        summary.termination = Termination::diverged;
        summary.message = "diverged: loss " + std::to_string(loss) + " in epoch " +
                          std::to_string(epoch) + ", batch " + std::to_string(batches + 1) +
                          " (try a smaller learning_rate)";
        publish();
        return summary;
      }
      velocity = momentum * velocity - learning_rate * gradient;  // Eq. (14)
      w += velocity;
      loss_sum += loss;
      ++batches;
    }
    EpochRecord record;
    record.epoch = epoch;
    record.train_loss = batches ? loss_sum / static_cast<double>(batches) : std::nan("");
    publish();
    record.validation_loss = hooks.validation_loss ? hooks.validation_loss(params) : std::nan("");
    record.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary.history.push_back(record);
    if (!w.allFinite()) {
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
      if (options.early_stop_patience > 0) best_params = w;
    }
    if (options.early_stop_patience > 0 &&
        epoch - summary.best_epoch >= options.early_stop_patience) {
      if (best_params.size() == w.size()) w = best_params;
      publish();
      summary.termination = Termination::early_stop;
      summary.message = "early stop: no validation improvement for " +
                        std::to_string(options.early_stop_patience) + " epochs; restored epoch " +
                        std::to_string(summary.best_epoch);
      return summary;
    }
  }
  summary.termination = Termination::max_epochs;
  summary.message = "completed " + std::to_string(options.epochs) + " epochs";
  publish();
  return summary;
}

}  // namespace

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
  if (options.precision == Precision::float64) {
    return sgdm_loop<double>(objective, params, params, options, shuffle_rng, hooks);
  }
  if (!objective.has_float32()) {
    throw OptionError("precision", "float32", "this model has no float32 training; use float64");
  }
  Eigen::VectorXf w = params.cast<float>();
  return sgdm_loop<float>(objective, params, w, options, shuffle_rng, hooks);
}

TrainerDef sgdm_trainer() {
  TrainerCapabilities can;
  can.dropout = can.mini_batches = can.validation_stop = can.float32 = true;
  return make_trainer<SgdmOptions>(
      "sgdm", "stochastic gradient descent with momentum (seed 000 Eq. 14)", sgdm_fields(), can,
      TrainerHistory::epochs,
      [](const SgdmOptions& options, const MlpTrainingProblem& p, Eigen::VectorXd& params) {
        Rng dropout_rng(p.seed, "dropout");
        Rng shuffle_rng(p.seed, "shuffle");
        MlpRegressionObjective objective(p.mlp, p.x, p.y, dropout_rng);
        return train_sgdm(objective, params, options, shuffle_rng,
                          SgdmHooks{p.hooks.validation_loss, p.hooks.on_epoch});
      });
}

}  // namespace cnclab
