#pragma once
// Real-time NARX prediction of one axis (seed 002 Sec. III, Fig. 12: the
// trained networks run in closed loop inside the controller's 1 ms cycle):
// per tick one reference velocity in (and, for a network with more input
// channels, their values), one predicted following error out, in physical
// units, the network's own past outputs fed back (the parallel
// configuration of Eq. 1).
//
// Construction copies the network and its normalisation and sizes every
// buffer; it may allocate and throws cnclab::Error on an inconsistent model.
// reset() and step() never allocate and never throw: bad input is reported
// by PredictorStatus and leaves the state and the outputs unchanged.
#include <Eigen/Core>
#include <span>

#include "cnclab/nn/minmax.hpp"
#include "cnclab/nn/narx.hpp"

namespace cnclab {

enum class PredictorStatus {
  ok,
  non_finite_input,      // NaN or infinity in an input of the tick or the reset
  wrong_history_length,  // reset with a history of the wrong length
  wrong_input_count,     // a tick with other than one value per input channel
  undefined_tangent,     // contour estimate: zero or non-finite path derivative
};
const char* to_string(PredictorStatus status) noexcept;

// A trained per-axis network as the predictor needs it.
struct NarxAxisModel {
  NarxOptions options;     // architecture (delays, hidden units, activation)
  Eigen::VectorXd params;  // trained weights and biases, Narx layout
  // One feature per input channel (options.inputs): reference velocity
  // [mm/s] first, then any further channel in its own units.
  MinMaxNormaliser input;
  MinMaxNormaliser output;  // 1 feature: following error [mm] <-> network output
};

class NarxPredictor {
 public:
  // Throws cnclab::Error (or OptionError for bad options) when params does
  // not fit the architecture or a normaliser does not have one fitted
  // feature per channel (output: exactly one). Starts at rest (reset()).
  explicit NarxPredictor(NarxAxisModel model);

  // Rest state: every past input and past error 0 (physical units), the
  // start of a trajectory from standstill.
  void reset() noexcept;
  // State from measured history, oldest first, the last value at t - 1:
  // velocity_history() past ticks of the inputs (each tick's channels
  // together: C values) and error_history() past following errors (the
  // batch simulation's initial states, Narx::simulate_closed_loop with the
  // series starting at t - first_step()). Wrong lengths or non-finite
  // values: status, state unchanged.
  PredictorStatus reset(std::span<const double> past_velocities,
                        std::span<const double> past_errors) noexcept;

  // One tick: reference velocity v(t) [mm/s] -> predicted following error
  // e(t) [mm] into `error`. Non-finite v: status, state and `error`
  // unchanged. A single-channel network only (else wrong_input_count).
  PredictorStatus step(double velocity, double& error) noexcept;
  // The same with every channel's value of the tick (size C, velocity first).
  PredictorStatus step(std::span<const double> inputs, double& error) noexcept;

  // Past ticks the regressor reads besides t: first_input_delay +
  // input_delays - 1.
  std::size_t velocity_history() const noexcept {
    return static_cast<std::size_t>(inputs_.rows()) - 1;
  }
  std::size_t channels() const noexcept { return static_cast<std::size_t>(inputs_.cols()); }
  std::size_t error_history() const noexcept { return errors_.size(); }  // D_E
  const NarxAxisModel& model() const noexcept { return model_; }

 private:
  NarxAxisModel model_;
  Narx narx_;
  // Normalised histories, newest first: between ticks inputs_.row(0) =
  // v(t - 1) (one column per channel) and errors_[0] = e(t - 1); a tick
  // pushes v(t) in front, builds the regressor, then pushes e(t). inputs_
  // has room for v(t) and the velocity_history() older ticks.
  Eigen::MatrixXd inputs_;
  Eigen::VectorXd errors_;
  Eigen::VectorXd regressor_, hidden_;  // Narx::step's buffers
};

}  // namespace cnclab
