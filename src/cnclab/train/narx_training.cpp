#include "cnclab/train/narx_training.hpp"

#include <algorithm>
#include <string>

#include "cnclab/core/error.hpp"

namespace cnclab {

NarxOpenLoopObjective::NarxOpenLoopObjective(const Narx& narx, const Eigen::VectorXd& v,
                                             const Eigen::VectorXd& e)
    : inputs_(narx.open_loop_regressors(v, e)),
      targets_(e.tail(e.size() - narx.first_step()).transpose()),
      static_(narx.mlp(), inputs_, targets_) {}

NarxClosedLoopObjective::NarxClosedLoopObjective(const Narx& narx, const Eigen::VectorXd& v,
                                                 const Eigen::VectorXd& e, Eigen::Index horizon)
    : narx_(narx), v_(v), e_(e), horizon_(horizon) {
  narx.open_loop_regressors(v, e);  // the same checks on the series (lengths, NaN)
  if (horizon < 0) throw Error("closed-loop horizon " + std::to_string(horizon) + " < 0");
}

void NarxClosedLoopObjective::evaluate(const Eigen::VectorXd& params, Eigen::Index first,
                                       Eigen::Index count, Eigen::Ref<Eigen::VectorXd> residuals,
                                       Eigen::MatrixXd* jacobian) {
  const bool same = cached_params_.size() == params.size() && cached_params_ == params;
  if (!same || (jacobian != nullptr && !has_jacobian_)) {
    has_jacobian_ = jacobian != nullptr;
    simulate(params);
    cached_params_ = params;
  }
  residuals = residuals_.segment(first, count);
  if (jacobian != nullptr) *jacobian = jacobian_.middleRows(first, count);
}

void NarxClosedLoopObjective::simulate(const Eigen::VectorXd& params) {
  const Eigen::Index steps = num_residuals(), t0 = narx_.first_step();
  const Eigen::Index window = horizon_ > 0 ? std::min(horizon_, steps) : steps;
  if (window == steps) {  // one window: no copies of the series or the Jacobian
    residuals_ = narx_.simulate_closed_loop(params, v_, e_, has_jacobian_ ? &jacobian_ : nullptr) -
                 e_.tail(steps);
    return;
  }
  residuals_.resize(steps);
  if (has_jacobian_) jacobian_.resize(steps, num_parameters());
  Eigen::MatrixXd window_jacobian;
  // Window [s, s + n) of the residual rows predicts steps t0 + s .. t0 + s + n - 1
  // from the measured states e(s .. s + t0 - 1) and the inputs from s on.
  for (Eigen::Index s = 0; s < steps; s += window) {
    const Eigen::Index n = std::min(window, steps - s);
    const Eigen::VectorXd v = v_.segment(s, t0 + n), e = e_.segment(s, t0 + n);
    residuals_.segment(s, n) =
        narx_.simulate_closed_loop(params, v, e, has_jacobian_ ? &window_jacobian : nullptr) -
        e.tail(n);
    if (has_jacobian_) jacobian_.middleRows(s, n) = window_jacobian;
  }
}

void NarxTrainingOptions::validate() const {
  const auto prefixed = [](const char* stage, const TrainbrOptions& o) {
    try {
      o.validate();
    } catch (const OptionError& e) {
      throw OptionError(std::string(stage) + "." + e.field(), e.value(), e.rule());
    }
  };
  prefixed("open_loop", open_loop);
  prefixed("closed_loop", closed_loop);
  if (!run_open_loop && !run_closed_loop) {
    throw OptionError("run_open_loop, run_closed_loop", "false, false", "run at least one stage");
  }
}

NarxTrainingResult train_narx(const Narx& narx, const Eigen::VectorXd& v, const Eigen::VectorXd& e,
                              Eigen::VectorXd& params, const NarxTrainingOptions& options) {
  options.validate();
  if (params.size() != static_cast<Eigen::Index>(narx.num_parameters())) {
    throw Error("train_narx: " + std::to_string(params.size()) + " parameters, the network has " +
                std::to_string(narx.num_parameters()));
  }
  NarxTrainingResult result;
  if (options.run_open_loop) {
    NarxOpenLoopObjective open(narx, v, e);
    result.open_loop = train_trainbr(open, params, options.open_loop);
  }
  if (options.run_closed_loop) {
    NarxClosedLoopObjective closed(narx, v, e);
    result.closed_loop = train_trainbr(closed, params, options.closed_loop);
  }
  return result;
}

}  // namespace cnclab
