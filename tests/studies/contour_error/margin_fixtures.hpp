#pragma once
// Shared by the margin tests: a predictor that predicts no error at all and
// a small planning dataset with two feed factors. In headers, since unity
// builds compile a target's tests in one file.
#include "cnclab/core/config.hpp"
#include "cnclab/data/generator.hpp"
#include "cnclab/studies/contour_error/contour_predictor.hpp"

namespace cnclab::testing {

// e = 0 whatever the input: zero weights, output range symmetric about 0.
inline NarxAxisModel zero_model() {
  NarxOptions o;
  o.input_delays = o.feedback_delays = 1;
  o.hidden = 1;
  return {o, Eigen::VectorXd::Zero(5),
          MinMaxNormaliser(Eigen::VectorXd::Constant(1, -300), Eigen::VectorXd::Constant(1, 300)),
          MinMaxNormaliser(Eigen::VectorXd::Constant(1, -1), Eigen::VectorXd::Constant(1, 1))};
}

inline const Dataset& plans() {
  static const Dataset d = [] {
    const ConfigDocument doc = ConfigDocument::parse(
        "dataset:\n  generator: following_error\n  options:\n"
        "    path: {control_points: 12}\n    runs: 1\n    smoothing: 1\n    samples: 1200\n"
        "    feed_factors: [1, 0.5]\n",
        "test.yaml");
    Rng rng(5);
    return read_generator(doc.root().section("dataset"))->generate(rng);
  }();
  return d;
}

}  // namespace cnclab::testing
