#include "cnclab/nn/mlp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

// Central differences with h = 1e-6 on O(1) values: truncation O(h^2) and
// rounding O(eps/h) both ~1e-10; 1e-6 relative leaves a wide margin.
constexpr double kFdStep = 1e-6;
constexpr double kGradTol = 1e-6;

MlpOptions options(Activation hidden, Activation output, std::vector<std::size_t> widths,
                   std::size_t in, std::size_t out) {
  MlpOptions o;
  o.inputs = in;
  o.outputs = out;
  o.hidden = std::move(widths);
  o.hidden_activation = hidden;
  o.output_activation = output;
  o.weights = {Initializer::Kind::normal, 0.0, 0.5};
  return o;
}

// Compares loss_and_gradient with central differences of the loss, holding
// the dropout masks in the workspace fixed.
void check_gradient(const MlpOptions& o, std::uint64_t seed) {
  const Mlp mlp(o);
  Rng rng(seed);
  Eigen::VectorXd p;
  mlp.initialise(p, rng);
  const Eigen::Index batch = 5;
  Eigen::MatrixXd x(o.inputs, batch), y(o.outputs, batch);
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = rng.normal();
  for (Eigen::Index i = 0; i < y.size(); ++i) y.data()[i] = rng.normal();
  Mlp::Workspace ws;
  mlp.prepare(ws, batch);
  mlp.draw_dropout_masks(ws, rng);
  Eigen::VectorXd g, scratch;
  mlp.loss_and_gradient(p, x, y, ws, g);
  for (Eigen::Index k = 0; k < p.size(); ++k) {
    Eigen::VectorXd plus = p, minus = p;
    plus[k] += kFdStep;
    minus[k] -= kFdStep;
    const double fd = (mlp.loss_and_gradient(plus, x, y, ws, scratch) -
                       mlp.loss_and_gradient(minus, x, y, ws, scratch)) /
                      (2 * kFdStep);
    ASSERT_NEAR(g[k], fd, kGradTol * std::max(1.0, std::abs(fd)))
        << "parameter " << k << " of " << p.size();
  }
}

TEST(Mlp, GradientMatchesFiniteDifferencesForEveryActivation) {
  // ReLU's kink: with random weights no pre-activation lands within h of 0
  // for these seeds (a kink would show as one large mismatch).
  for (Activation a :
       {Activation::relu, Activation::tanh, Activation::sigmoid, Activation::linear}) {
    SCOPED_TRACE(to_string(a));
    check_gradient(options(a, Activation::linear, {6, 4}, 3, 2), 11);
    check_gradient(options(Activation::tanh, a, {5}, 4, 1), 12);
  }
}

TEST(Mlp, GradientMatchesFiniteDifferencesWithFixedDropoutMasks) {
  for (auto placement : {DropoutPlacement::between_hidden, DropoutPlacement::after_every_hidden}) {
    auto o = options(Activation::tanh, Activation::linear, {7, 6, 5}, 3, 2);
    o.dropout_keep_probability = 0.6;
    o.dropout_placement = placement;
    check_gradient(o, 13);
  }
}

TEST(Mlp, ParameterCountIsSumOfInPlusOneTimesOut) {
  const Mlp mlp(options(Activation::relu, Activation::linear, {28, 20}, 73, 1));
  EXPECT_EQ(mlp.num_parameters(), (73u + 1) * 28 + (28u + 1) * 20 + (20u + 1) * 1);
}

TEST(Mlp, DropoutPlacementFollowsSeed000ByDefault) {
  auto o = options(Activation::relu, Activation::linear, {28, 20}, 73, 1);
  o.dropout_keep_probability = 0.5;
  const Mlp between(o);
  EXPECT_TRUE(between.has_dropout(1));   // after the 28-unit layer
  EXPECT_FALSE(between.has_dropout(2));  // not after the last hidden layer
  EXPECT_FALSE(between.has_dropout(0));
  EXPECT_FALSE(between.has_dropout(3));
  o.dropout_placement = DropoutPlacement::after_every_hidden;
  EXPECT_TRUE(Mlp(o).has_dropout(2));
}

TEST(Mlp, DropoutMasksKeepShareAndInvertedScaling) {
  auto o = options(Activation::relu, Activation::linear, {400, 300}, 2, 1);
  o.dropout_keep_probability = 0.3;
  const Mlp mlp(o);
  Mlp::Workspace ws;
  mlp.prepare(ws, 50);
  Rng rng(7);
  mlp.draw_dropout_masks(ws, rng);
  const Eigen::MatrixXd& m = ws.mask[1];
  const double n = static_cast<double>(m.size());
  const double kept = static_cast<double>((m.array() > 0).count());
  // Binomial(n, 0.3): 5-sigma bound on the kept share.
  EXPECT_NEAR(kept / n, 0.3, 5 * std::sqrt(0.3 * 0.7 / n));
  // Kept units are scaled by 1/p, so E[mask] = 1.
  EXPECT_TRUE(((m.array() == 0) || (m.array() == 1.0 / 0.3)).all());
  EXPECT_NEAR(m.mean(), 1.0, 5 * std::sqrt(0.7 / 0.3 / n));
}

// The masks are the Bernoulli draws r = [u < p] of the documented rule, u =
// Rng::uniform() taken layer by layer in column-major order (the integer
// comparison the code uses instead must give the same masks), in both
// precisions, including keep probabilities that are not multiples of 2^-53
// and one within an ulp of 1.
TEST(Mlp, DropoutMasksAreUniformDrawsBelowTheKeepProbability) {
  for (const double p : {0.5, 0.3, 1.0 / 3.0, 0.9, std::nextafter(1.0, 0.0), 0x1.0p-40}) {
    auto o = options(Activation::relu, Activation::linear, {30, 20, 10}, 2, 1);
    o.dropout_keep_probability = p;
    const Mlp mlp(o);
    Mlp::Workspace ws;
    Mlp::Workspace32 ws32;
    mlp.prepare(ws, 64);
    mlp.prepare(ws32, 64);
    Rng rng(9), rng32(9), reference(9);
    mlp.draw_dropout_masks(ws, rng);
    mlp.draw_dropout_masks(ws32, rng32);
    for (std::size_t l = 1; l <= 2; ++l) {  // between_hidden: the first two hidden layers
      for (Eigen::Index i = 0; i < ws.mask[l].size(); ++i) {
        const bool keep = reference.uniform() < p;
        ASSERT_EQ(ws.mask[l].data()[i], keep ? 1.0 / p : 0.0) << "p " << p << " layer " << l;
        ASSERT_EQ(ws32.mask[l].data()[i], keep ? static_cast<float>(1.0 / p) : 0.0f);
      }
    }
    EXPECT_EQ(rng.next_u64(), reference.next_u64()) << "p " << p;
  }
}

TEST(Mlp, PredictIsDeterministicAndHasNoDropout) {
  auto o = options(Activation::relu, Activation::linear, {8, 8}, 3, 1);
  o.dropout_keep_probability = 0.5;
  const Mlp with_dropout(o);
  o.dropout_keep_probability = 1.0;
  const Mlp without(o);
  Rng rng(8);
  Eigen::VectorXd p;
  with_dropout.initialise(p, rng);
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(3, 10);
  EXPECT_EQ(with_dropout.predict(p, x), without.predict(p, x));
}

TEST(Mlp, PredictEqualsHandComputedForward) {
  MlpOptions o = options(Activation::relu, Activation::linear, {2}, 2, 1);
  const Mlp mlp(o);
  Eigen::VectorXd p(9);
  // W1 = [[1, -1], [2, 0.5]] (column-major: 1, 2, -1, 0.5), b1 = (0.5, -1),
  // W2 = [3, -2], b2 = 0.25.
  p << 1, 2, -1, 0.5, 0.5, -1, 3, -2, 0.25;
  Eigen::MatrixXd x(2, 1);
  x << 1, 2;
  // z1 = (1 - 2 + 0.5, 2 + 1 - 1) = (-0.5, 2) -> relu (0, 2); y = -4 + 0.25.
  EXPECT_DOUBLE_EQ(mlp.predict(p, x)(0, 0), -3.75);
}

TEST(Mlp, OptionsValidated) {
  auto o = options(Activation::relu, Activation::linear, {4}, 2, 1);
  o.dropout_keep_probability = 0.0;
  EXPECT_THROW(o.validate(), OptionError);
  o.dropout_keep_probability = 1.0;
  o.hidden = {0};
  EXPECT_THROW(o.validate(), OptionError);
}

// validate() checks the rules its config fields declare (nn/mlp_fields.hpp),
// naming the YAML key: every case breaks one declared rule.
TEST(Mlp, ValidateChecksTheDeclaredRulesUnderTheirKeys) {
  const auto error_of = [](const std::function<void(MlpOptions&)>& change) {
    MlpOptions o;
    change(o);
    try {
      o.validate();
    } catch (const OptionError& e) {
      return e.field() + ": " + e.rule();
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of([](MlpOptions& o) { o.dropout_keep_probability = 1.5; }),
            "dropout.keep_probability: must be in (0, 1]");
  EXPECT_EQ(error_of([](MlpOptions& o) { o.dropout_mc_samples = 0; }),
            "dropout.mc_samples: must be in [1, 1000000]");
  EXPECT_EQ(error_of([](MlpOptions& o) { o.hidden = {28, 0}; }), "hidden: must be in [1, 100000]");
  EXPECT_EQ(error_of([](MlpOptions& o) { o.weights.std = -1; }),
            "init.weights.std: must be a finite number >= 0");
  EXPECT_EQ(error_of([](MlpOptions& o) { o.weights.mean = std::nan(""); }),
            "init.weights.mean: must be a finite number");
  EXPECT_EQ(error_of([](MlpOptions& o) {
              o.biases.kind = Initializer::Kind::uniform;
              o.biases.low = 1;
              o.biases.high = 0;
            }).substr(0, 5),
            "high:");  // the cross-field rule, Initializer::validate
  EXPECT_EQ(error_of([](MlpOptions&) {}), "no error");
}

TEST(Initializer, MomentsAndBounds) {
  constexpr Eigen::Index kIn = 300, kOut = 200;
  Eigen::MatrixXd w(kOut, kIn);
  Rng rng(9);
  const double n = static_cast<double>(w.size());
  Initializer{Initializer::Kind::normal, 1.0, 2.0}.fill(w, kIn, kOut, rng);
  EXPECT_NEAR(w.mean(), 1.0, 5 * 2.0 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt((w.array() - w.mean()).square().mean()), 2.0, 0.02);
  Initializer u{Initializer::Kind::uniform};
  u.low = -3;
  u.high = -1;
  u.fill(w, kIn, kOut, rng);
  EXPECT_GE(w.minCoeff(), -3);
  EXPECT_LT(w.maxCoeff(), -1);
  Initializer{Initializer::Kind::xavier}.fill(w, kIn, kOut, rng);
  EXPECT_LE(w.cwiseAbs().maxCoeff(), std::sqrt(6.0 / (kIn + kOut)));
  EXPECT_GT(w.cwiseAbs().maxCoeff(), 0.99 * std::sqrt(6.0 / (kIn + kOut)));
  Initializer{Initializer::Kind::he}.fill(w, kIn, kOut, rng);
  EXPECT_NEAR(std::sqrt(w.array().square().mean()), std::sqrt(2.0 / kIn), 0.002);
}

}  // namespace
}  // namespace cnclab
