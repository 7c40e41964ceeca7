#pragma once
// A NARX axis model with random weights whose closed loop is a contraction:
// the feedback weights are scaled so that sum_k |de(t)/de(t-k)| <=
// sum_k sum_i |w2_i| |W1(i, D_V + k - 1)| max f' <= kFeedbackGain < 1 (tanh and
// sigmoid have f' <= 1). Rounding differences then cannot grow along a long
// sequence, and the outputs stay bounded, as a trained stable network's do.
// Physical ranges: velocity +-300 mm/s (seed 002's limit), following error
// [-0.2, 0.25] mm.
#include <cmath>

#include "cnclab/core/rng.hpp"
#include "cnclab/nn/narx_predictor.hpp"

namespace cnclab::testing {

inline NarxAxisModel stable_narx_model(const NarxOptions& options, std::uint64_t seed) {
  constexpr double kFeedbackGain = 0.9;
  const Narx narx(options);
  NarxAxisModel m{
      options, Eigen::VectorXd(narx.num_parameters()),
      MinMaxNormaliser(Eigen::VectorXd::Constant(1, -300.0), Eigen::VectorXd::Constant(1, 300.0)),
      MinMaxNormaliser(Eigen::VectorXd::Constant(1, -0.2), Eigen::VectorXd::Constant(1, 0.25))};
  Rng rng(seed);
  narx.initialise(m.params, rng);
  const auto h = static_cast<Eigen::Index>(options.hidden);
  const auto dv = static_cast<Eigen::Index>(options.input_delays);
  const Eigen::Index n = narx.num_inputs();
  Eigen::Map<Eigen::MatrixXd> w1(m.params.data(), h, n);
  const Eigen::Map<const Eigen::VectorXd> w2(m.params.data() + h * n + h, h);
  const double gain = (w2.cwiseAbs().transpose() * w1.rightCols(n - dv).cwiseAbs()).sum();
  if (gain > kFeedbackGain) w1.rightCols(n - dv) *= kFeedbackGain / gain;
  return m;
}

// Reference velocity [mm/s] of one axis at tick t: smooth, within +-300,
// with reversals (the feedback and delays matter), phase per axis.
inline double test_velocity(Eigen::Index t, double phase) {
  const double s = static_cast<double>(t) * 1e-3;
  return 200.0 * std::sin(2.1 * s + phase) + 90.0 * std::sin(13.0 * s + 0.5 * s * s + phase);
}

}  // namespace cnclab::testing
