#pragma once
// The end of an epoch of a mini-batch trainer (sgdm, adam), one for both:
// the epoch's record (mean mini-batch loss, validation loss, wall time),
// then the stops in their order: divergence (weights not finite), the
// epoch hook, and the validation stop (early_stop_patience epochs without a
// lower validation loss; the best weights restored).
#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "cnclab/train/summary.hpp"

namespace cnclab {

// Vector: the type of the weights the trainer updates (double or float).
template <class Vector>
class EpochEnd {
 public:
  // patience: early_stop_patience (0: no validation stop).
  EpochEnd(std::size_t patience, std::chrono::steady_clock::time_point start)
      : patience_(patience), start_(start) {}

  // After epoch `epoch` whose `batches` mini-batch losses sum to `loss_sum`:
  // `w` the trained weights, `params` what the hooks see (made from w by
  // `publish`). True when training stops; summary's termination and message
  // then say why.
  template <class Hooks, class Publish>
  bool operator()(std::size_t epoch, double loss_sum, std::size_t batches, Vector& w,
                  const Eigen::VectorXd& params, const Publish& publish, const Hooks& hooks,
                  Summary& summary) {
    EpochRecord record;
    record.epoch = epoch;
    record.train_loss = batches ? loss_sum / static_cast<double>(batches) : std::nan("");
    publish();
    record.validation_loss = hooks.validation_loss ? hooks.validation_loss(params) : std::nan("");
    record.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    summary.history.push_back(record);
    if (!w.allFinite()) {
      summary.termination = Termination::diverged;
      summary.message = "diverged: parameters not finite after epoch " + std::to_string(epoch);
      return true;
    }
    if (hooks.on_epoch && !hooks.on_epoch(record, params)) {
      summary.termination = Termination::stopped_by_callback;
      summary.message = "stopped by callback after epoch " + std::to_string(epoch);
      return true;
    }
    if (hooks.validation_loss && record.validation_loss < best_validation_) {
      best_validation_ = record.validation_loss;
      summary.best_epoch = epoch;
      if (patience_ > 0) best_ = w;
    }
    if (patience_ > 0 && epoch - summary.best_epoch >= patience_) {
      if (best_.size() == w.size()) w = best_;
      publish();
      summary.termination = Termination::early_stop;
      summary.message = "early stop: no validation improvement for " + std::to_string(patience_) +
                        " epochs; restored epoch " + std::to_string(summary.best_epoch);
      return true;
    }
    return false;
  }

 private:
  std::size_t patience_;
  std::chrono::steady_clock::time_point start_;
  Vector best_;
  double best_validation_ = std::numeric_limits<double>::infinity();
};

}  // namespace cnclab
