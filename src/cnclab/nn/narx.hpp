#pragma once
// NARX network (seed 002 Eq. 1): one tanh hidden layer, linear output,
//   e(t) = sum_i w^o_i f(h_i(t)) + b^o,
//   h_i(t) = sum_c sum_j w^v_icj v_c(t - d_j) + sum_{k=1..D_E} w^e_ik e(t - k) + b_i,
// input v = axis reference velocity, output e = axis following error. Seed
// 002's network is SISO (one input channel c = 0); `inputs` > 1 adds
// exogenous channels with the same delays (e.g. the axis's direction of
// motion, motion/axis_direction.hpp), each a column of the input series.
//
// Delay convention: the input delays are d_j = first_input_delay + j,
// j = 0..D_V-1. Default first_input_delay = 0, i.e. Eq. 1 with the current
// command v(t) (its Fig. 2 caption: "v(t) is the current axis velocity
// command"): the interpolator has v(t) before the drives act on it, and the
// following error of tick t already responds to it through the velocity
// feed-forward, so leaving it out delays the prediction by a tick.
// first_input_delay = 1 gives MATLAB's narxnet(1:D_V, 1:D_E). Feedback
// delays are always 1..D_E (e(t) cannot feed itself).
//
// Parameters: one flat vector in the layout of an Mlp with inputs
// C D_V + D_E (C = inputs; regressor order below), hidden {H}, one linear output:
// W1 (H x (D_V + D_E), column-major), b1 (H), W2 (1 x H), b2.
#include <Eigen/Core>
#include <cstddef>

#include "cnclab/core/rng.hpp"
#include "cnclab/nn/activation.hpp"
#include "cnclab/nn/initializer.hpp"
#include "cnclab/nn/mlp.hpp"

namespace cnclab {

struct NarxOptions {
  std::size_t input_delays = 4;     // D_V >= 1, number of velocity inputs (seed 002: 4)
  std::size_t feedback_delays = 4;  // D_E >= 1, fed-back errors e(t-1..t-D_E) (seed 002: 4)
  std::size_t hidden = 12;          // H >= 1 (seed 002: 12)
  Activation hidden_activation = Activation::tanh;  // seed 002: tanh; output linear
  std::size_t first_input_delay = 0;  // 0: Eq. 1 with v(t); 1: MATLAB narxnet(1:D_V, ...)
  std::size_t inputs = 1;             // C >= 1 exogenous channels (seed 002: 1, the velocity)
  // Initial weights and biases U(-0.5, 0.5) (small: tanh units start in
  // their linear range; MATLAB's Nguyen-Widrow is not reproduced).
  Initializer weights{Initializer::Kind::uniform, 0.0, 1.0, -0.5, 0.5};
  Initializer biases{Initializer::Kind::uniform, 0.0, 1.0, -0.5, 0.5};

  // OptionError naming the field: delays >= 1, hidden >= 1, inputs >= 1,
  // first_input_delay in {0, 1}, initialisers valid.
  void validate() const;
};

class Narx {
 public:
  explicit Narx(NarxOptions options);  // validates

  const NarxOptions& options() const { return options_; }
  // The static network of the series-parallel configuration (same layout).
  const Mlp& mlp() const { return mlp_; }
  std::size_t num_parameters() const { return mlp_.num_parameters(); }
  // Regressor length C D_V + D_E.
  Eigen::Index num_inputs() const {
    return static_cast<Eigen::Index>(options_.inputs * options_.input_delays +
                                     options_.feedback_delays);
  }
  // First step with a full regressor: max(largest input delay, D_E).
  Eigen::Index first_step() const;
  void initialise(Eigen::VectorXd& params, Rng& rng) const { mlp_.initialise(params, rng); }

  // The input series: T rows, one column per channel (a VectorXd is the
  // single channel of seed 002).
  using Inputs = Eigen::Ref<const Eigen::MatrixXd>;

  // Series-parallel regressors (one column per step t = first_step()..T-1):
  // [v_0(t - d_0), ..., v_0(t - d_{D_V-1}), v_1(t - d_0), ..., e(t-1), ...,
  // e(t-D_E)] with the measured e. v (T x C) and e have T > first_step() rows.
  Eigen::MatrixXd open_loop_regressors(const Inputs& v, const Eigen::VectorXd& e) const;

  // Parallel (closed-loop) simulation: e_hat(t) for t = first_step()..T-1
  // with the network's own past outputs fed back; the first first_step()
  // values of `e_initial` are the initial states (measured errors), later
  // values are not read. If `jacobian` is given it receives the exact dynamic
  // Jacobian d e_hat(t) / dw ((T - first_step()) x W) by forward-mode (RTRL)
  // recursion through the feedback delays:
  //   S(t) = df/dw|x(t) + sum_k df/de(t-k)|x(t) S(t-k),  S = 0 on initial states.
  Eigen::VectorXd simulate_closed_loop(const Eigen::VectorXd& params, const Inputs& v,
                                       const Eigen::VectorXd& e_initial,
                                       Eigen::MatrixXd* jacobian = nullptr) const;

  // Eq. 1 at one step: from the regressor x (num_inputs(), layout above)
  // writes the hidden activations f(h_i) into `hidden` (size H) and returns
  // e(t). Sizes are the caller's contract (params: num_parameters()). No
  // heap allocation: simulate_closed_loop and the real-time predictor
  // (narx_predictor.hpp) both step through here, so they agree bit for bit.
  double step(const Eigen::VectorXd& params, const Eigen::VectorXd& x,
              Eigen::VectorXd& hidden) const noexcept;

 private:
  void check_series(const Inputs& v, const Eigen::VectorXd& e) const;

  NarxOptions options_;
  Mlp mlp_;
};

}  // namespace cnclab
