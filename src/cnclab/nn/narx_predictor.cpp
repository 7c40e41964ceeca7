#include "cnclab/nn/narx_predictor.hpp"

#include <cmath>
#include <string>

#include "cnclab/core/enum_names.hpp"
#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

void check_features(const MinMaxNormaliser& n, std::size_t wanted, const char* what) {
  if (n.features() != static_cast<Eigen::Index>(wanted)) {
    throw Error(std::string("NARX predictor: the ") + what + " normaliser has " +
                std::to_string(n.features()) + " fitted features, need exactly " +
                std::to_string(wanted));
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

// The same for a history of ticks (rows), each tick's channels a row.
void push_front_row(Eigen::MatrixXd& history) noexcept {
  for (Eigen::Index i = history.rows() - 1; i > 0; --i) history.row(i) = history.row(i - 1);
}

constexpr EnumName<PredictorStatus> kPredictorStatusNames[] = {
    {PredictorStatus::ok, "ok"},
    {PredictorStatus::non_finite_input, "non-finite input"},
    {PredictorStatus::wrong_history_length, "wrong history length"},
    {PredictorStatus::wrong_input_count, "wrong number of input channels"},
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
  check_features(model_.input, model_.options.inputs, "input (velocity, other channels)");
  check_features(model_.output, 1, "output (following error)");
  const auto& o = model_.options;
  inputs_.resize(static_cast<Eigen::Index>(o.first_input_delay + o.input_delays),
                 static_cast<Eigen::Index>(o.inputs));
  errors_.resize(static_cast<Eigen::Index>(o.feedback_delays));
  regressor_.resize(narx_.num_inputs());
  hidden_.resize(static_cast<Eigen::Index>(o.hidden));
  reset();
}

void NarxPredictor::reset() noexcept {
  for (Eigen::Index c = 0; c < inputs_.cols(); ++c) {
    inputs_.col(c).setConstant(model_.input.transform(c, 0.0));
  }
  errors_.setConstant(model_.output.transform(0, 0.0));
}

PredictorStatus NarxPredictor::reset(std::span<const double> past_velocities,
                                     std::span<const double> past_errors) noexcept {
  const std::size_t c = channels();
  if (past_velocities.size() != velocity_history() * c || past_errors.size() != error_history()) {
    return PredictorStatus::wrong_history_length;
  }
  if (!all_finite(past_velocities) || !all_finite(past_errors)) {
    return PredictorStatus::non_finite_input;
  }
  // Between ticks both histories are newest first from t - 1 (step() pushes
  // v(t) in front); inputs_'s last row is pushed out by the next tick.
  const std::size_t nv = velocity_history();
  for (std::size_t i = 0; i < nv; ++i) {
    for (std::size_t k = 0; k < c; ++k) {
      inputs_(static_cast<Eigen::Index>(nv - 1 - i), static_cast<Eigen::Index>(k)) =
          model_.input.transform(static_cast<Eigen::Index>(k), past_velocities[i * c + k]);
    }
  }
  const std::size_t ne = past_errors.size();
  for (std::size_t i = 0; i < ne; ++i) {
    errors_[static_cast<Eigen::Index>(ne - 1 - i)] = model_.output.transform(0, past_errors[i]);
  }
  return PredictorStatus::ok;
}

PredictorStatus NarxPredictor::step(double velocity, double& error) noexcept {
  return step(std::span<const double>(&velocity, 1), error);
}

PredictorStatus NarxPredictor::step(std::span<const double> inputs, double& error) noexcept {
  if (inputs.size() != channels()) return PredictorStatus::wrong_input_count;
  if (!all_finite(inputs)) return PredictorStatus::non_finite_input;
  push_front_row(inputs_);
  for (Eigen::Index c = 0; c < inputs_.cols(); ++c) {
    inputs_(0, c) = model_.input.transform(c, inputs[static_cast<std::size_t>(c)]);
  }
  // Regressor of Eq. 1 (Narx layout): per channel v_c(t - d0 - j), then e(t - k).
  const auto dv = static_cast<Eigen::Index>(model_.options.input_delays);
  const auto d0 = static_cast<Eigen::Index>(model_.options.first_input_delay);
  for (Eigen::Index c = 0; c < inputs_.cols(); ++c) {
    for (Eigen::Index j = 0; j < dv; ++j) regressor_[c * dv + j] = inputs_(d0 + j, c);
  }
  regressor_.tail(errors_.size()) = errors_;
  const double e = narx_.step(model_.params, regressor_, hidden_);
  push_front(errors_, e);
  error = model_.output.inverse_transform(0, e);
  return PredictorStatus::ok;
}

}  // namespace cnclab
