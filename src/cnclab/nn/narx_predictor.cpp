#include "cnclab/nn/narx_predictor.hpp"

#include <cmath>
#include <string>

#include "cnclab/core/enum_names.hpp"
#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

void check_one_feature(const MinMaxNormaliser& n, const char* what) {
  if (n.features() != 1) {
    throw Error(std::string("NARX predictor: the ") + what + " normaliser has " +
                std::to_string(n.features()) + " fitted features, need exactly 1");
  }
}

bool all_finite(std::span<const double> values) noexcept {
  for (double x : values) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

// Shift a newest-first history by one and put `newest` in front.
void push_front(Eigen::VectorXd& history, double newest) noexcept {
  for (Eigen::Index i = history.size() - 1; i > 0; --i) history[i] = history[i - 1];
  history[0] = newest;
}

constexpr EnumName<PredictorStatus> kPredictorStatusNames[] = {
    {PredictorStatus::ok, "ok"},
    {PredictorStatus::non_finite_input, "non-finite input"},
    {PredictorStatus::wrong_history_length, "wrong history length"},
    {PredictorStatus::undefined_tangent, "undefined tangent (zero or non-finite path derivative)"}};

}  // namespace

const char* to_string(PredictorStatus status) noexcept {
  return enum_name(kPredictorStatusNames, status);
}

NarxPredictor::NarxPredictor(NarxAxisModel model)
    : model_(std::move(model)), narx_(model_.options) {
  if (model_.params.size() != static_cast<Eigen::Index>(narx_.num_parameters())) {
    throw Error("NARX predictor: " + std::to_string(model_.params.size()) +
                " parameters, the network has " + std::to_string(narx_.num_parameters()));
  }
  if (!model_.params.allFinite()) throw Error("NARX predictor: parameters contain NaN or infinity");
  check_one_feature(model_.input, "input (velocity)");
  check_one_feature(model_.output, "output (following error)");
  const auto& o = model_.options;
  velocities_.resize(static_cast<Eigen::Index>(o.first_input_delay + o.input_delays));
  errors_.resize(static_cast<Eigen::Index>(o.feedback_delays));
  regressor_.resize(narx_.num_inputs());
  hidden_.resize(static_cast<Eigen::Index>(o.hidden));
  reset();
}

void NarxPredictor::reset() noexcept {
  velocities_.setConstant(model_.input.transform(0, 0.0));
  errors_.setConstant(model_.output.transform(0, 0.0));
}

PredictorStatus NarxPredictor::reset(std::span<const double> past_velocities,
                                     std::span<const double> past_errors) noexcept {
  if (past_velocities.size() != velocity_history() || past_errors.size() != error_history()) {
    return PredictorStatus::wrong_history_length;
  }
  if (!all_finite(past_velocities) || !all_finite(past_errors)) {
    return PredictorStatus::non_finite_input;
  }
  // Between ticks both histories are newest first from t - 1 (step() pushes
  // v(t) in front); velocities_'s last slot is pushed out by the next tick.
  const std::size_t nv = past_velocities.size();
  for (std::size_t i = 0; i < nv; ++i) {
    velocities_[static_cast<Eigen::Index>(nv - 1 - i)] =
        model_.input.transform(0, past_velocities[i]);
  }
  const std::size_t ne = past_errors.size();
  for (std::size_t i = 0; i < ne; ++i) {
    errors_[static_cast<Eigen::Index>(ne - 1 - i)] = model_.output.transform(0, past_errors[i]);
  }
  return PredictorStatus::ok;
}

PredictorStatus NarxPredictor::step(double velocity, double& error) noexcept {
  if (!std::isfinite(velocity)) return PredictorStatus::non_finite_input;
  push_front(velocities_, model_.input.transform(0, velocity));
  // Regressor of Eq. 1 (Narx layout): v(t - d0 - j), then e(t - k).
  const auto dv = static_cast<Eigen::Index>(model_.options.input_delays);
  const auto d0 = static_cast<Eigen::Index>(model_.options.first_input_delay);
  for (Eigen::Index j = 0; j < dv; ++j) regressor_[j] = velocities_[d0 + j];
  regressor_.tail(errors_.size()) = errors_;
  const double e = narx_.step(model_.params, regressor_, hidden_);
  push_front(errors_, e);
  error = model_.output.inverse_transform(0, e);
  return PredictorStatus::ok;
}

}  // namespace cnclab
