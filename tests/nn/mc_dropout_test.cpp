// Monte-Carlo dropout inference (Mlp::predict_mc, Mlp::infer) against a
// direct average of forward passes computed here: the masks drawn again
// from a generator with the same seed in the documented order (per block of
// Mlp::kMcBlock samples, pass after pass, dropout layer after layer,
// column-major), each pass a plain scalar loop over the documented parameter
// layout (W_l column-major, then b_l), nothing shared with Mlp but Rng.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/nn/mlp.hpp"

namespace cnclab {
namespace {

MlpOptions tanh_net(std::vector<std::size_t> hidden, double keep, DropoutPlacement placement) {
  MlpOptions o;
  o.inputs = 3;
  o.outputs = 2;
  o.hidden = std::move(hidden);
  o.hidden_activation = Activation::tanh;
  o.output_activation = Activation::linear;
  o.dropout_keep_probability = keep;
  o.dropout_placement = placement;
  o.weights = {Initializer::Kind::normal, 0.0, 0.7};
  return o;
}

// The layers whose output is dropped (seed 000 step 6 or after every
// hidden layer), as the options document them.
std::vector<bool> dropped_layers(const MlpOptions& o) {
  const std::size_t L = o.hidden.size() + 1;
  std::vector<bool> drop(L + 1, false);
  const std::size_t last = o.dropout_placement == DropoutPlacement::between_hidden ? L - 1 : L;
  for (std::size_t l = 1; l < last; ++l) drop[l] = o.dropout_keep_probability < 1.0;
  return drop;
}

// Reference: sum over `passes` of the masked forward pass of the columns
// [start, start + n) of x, masks from `rng` in the documented order.
void add_reference_passes(const MlpOptions& o, const Eigen::VectorXd& p, const Eigen::MatrixXd& x,
                          Eigen::Index start, Eigen::Index n, std::size_t passes, Rng& rng,
                          Eigen::MatrixXd& sum) {
  std::vector<std::size_t> sizes = {o.inputs};
  sizes.insert(sizes.end(), o.hidden.begin(), o.hidden.end());
  sizes.push_back(o.outputs);
  const std::vector<bool> drop = dropped_layers(o);
  const double keep = o.dropout_keep_probability;
  for (std::size_t k = 0; k < passes; ++k) {
    // masks[l][j * n_l + i]: unit i of sample j
    std::vector<std::vector<double>> masks(sizes.size());
    for (std::size_t l = 0; l < sizes.size(); ++l) {
      if (!drop[l]) continue;
      for (Eigen::Index j = 0; j < n; ++j) {
        for (std::size_t i = 0; i < sizes[l]; ++i) {
          masks[l].push_back(rng.uniform() < keep ? 1.0 / keep : 0.0);
        }
      }
    }
    for (Eigen::Index j = 0; j < n; ++j) {
      std::vector<double> a(x.rows());
      for (Eigen::Index i = 0; i < x.rows(); ++i) a[static_cast<std::size_t>(i)] = x(i, start + j);
      std::size_t offset = 0;
      for (std::size_t l = 1; l < sizes.size(); ++l) {
        const std::size_t in = sizes[l - 1], out = sizes[l];
        std::vector<double> z(out);
        for (std::size_t r = 0; r < out; ++r) {
          double s = p[static_cast<Eigen::Index>(offset + in * out + r)];  // b_l
          for (std::size_t c = 0; c < in; ++c) {
            s += p[static_cast<Eigen::Index>(offset + c * out + r)] * a[c];  // W_l(r, c)
          }
          z[r] = l + 1 == sizes.size() ? s : std::tanh(s);
          if (drop[l]) z[r] *= masks[l][static_cast<std::size_t>(j) * out + r];
        }
        offset += (in + 1) * out;
        a = z;
      }
      for (std::size_t r = 0; r < a.size(); ++r)
        sum(static_cast<Eigen::Index>(r), start + j) += a[r];
    }
  }
}

Eigen::MatrixXd reference_mc(const MlpOptions& o, const Eigen::VectorXd& p,
                             const Eigen::MatrixXd& x, std::size_t passes, std::uint64_t seed) {
  Rng rng(seed);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(o.outputs), x.cols());
  for (Eigen::Index start = 0; start < x.cols(); start += Mlp::kMcBlock) {
    add_reference_passes(o, p, x, start, std::min(Mlp::kMcBlock, x.cols() - start), passes, rng,
                         sum);
  }
  return sum / static_cast<double>(passes);
}

Eigen::MatrixXd random_inputs(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  Rng rng(seed);
  Eigen::MatrixXd x(rows, cols);
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = rng.normal();
  return x;
}

// A network of `o` with initial parameters from `seed`.
struct Net {
  Mlp mlp;
  Eigen::VectorXd p;
  Net(const MlpOptions& o, std::uint64_t seed) : mlp(o) {
    Rng init(seed);
    mlp.initialise(p, init);
  }
};

TEST(McDropout, MeanEqualsDirectAverageOfPassesWithTheSameMasks) {
  for (const auto placement :
       {DropoutPlacement::between_hidden, DropoutPlacement::after_every_hidden}) {
    const MlpOptions o = tanh_net({6, 5, 4}, 0.6, placement);
    const Net net(o, 11);
    const Mlp& mlp = net.mlp;
    const Eigen::VectorXd& p = net.p;
    const Eigen::MatrixXd x = random_inputs(3, 37, 12);
    Rng rng(99);
    const Eigen::MatrixXd mc = mlp.predict_mc(p, x, 25, rng);
    const Eigen::MatrixXd expected = reference_mc(o, p, x, 25, 99);
    // Sums of 25 passes of O(1) values, each summed in another order: ~1e-15.
    EXPECT_LT((mc - expected).cwiseAbs().maxCoeff(), 1e-12) << to_string(placement);
    // The mean of masked passes of a tanh network is not its deterministic pass.
    EXPECT_GT((mc - mlp.predict(p, x)).cwiseAbs().maxCoeff(), 1e-3);
  }
}

TEST(McDropout, BlocksOfSamplesDrawTheirMasksInTurn) {
  // More samples than one block: the second block's masks follow the first's.
  const MlpOptions o = tanh_net({4, 3}, 0.5, DropoutPlacement::between_hidden);
  const Net net(o, 3);
  const Mlp& mlp = net.mlp;
  const Eigen::VectorXd& p = net.p;
  const Eigen::MatrixXd x = random_inputs(3, Mlp::kMcBlock + 9, 4);
  Rng rng(5);
  const Eigen::MatrixXd mc = mlp.predict_mc(p, x, 3, rng);
  EXPECT_LT((mc - reference_mc(o, p, x, 3, 5)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(McDropout, LinearNetworkConvergesToTheDeterministicPass) {
  // Closed form: with linear units and inverted dropout (E[r / p] = 1) the
  // expected output is the deterministic pass, so the MC mean of N passes
  // is within a few standard errors s / sqrt(N) of it.
  MlpOptions o = tanh_net({6, 5}, 0.5, DropoutPlacement::after_every_hidden);
  o.hidden_activation = Activation::linear;
  const Net net(o, 21);
  const Mlp& mlp = net.mlp;
  const Eigen::VectorXd& p = net.p;
  const Eigen::MatrixXd x = random_inputs(3, 4, 22);
  Rng rng(23);
  // The spread of one pass, from 400 single passes.
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(2, 4), sum_sq = Eigen::MatrixXd::Zero(2, 4);
  for (int k = 0; k < 400; ++k) {
    const Eigen::MatrixXd one = mlp.predict_mc(p, x, 1, rng);
    sum += one;
    sum_sq += one.cwiseProduct(one);
  }
  const Eigen::ArrayXXd sd = (sum_sq / 400 - (sum / 400).cwiseProduct(sum / 400)).array().sqrt();
  const std::size_t n = 20000;
  const Eigen::ArrayXXd error = (mlp.predict_mc(p, x, n, rng) - mlp.predict(p, x)).array().abs();
  EXPECT_TRUE((error <= 5 * sd / std::sqrt(static_cast<double>(n)) + 1e-12).all()) << error << "\n"
                                                                                   << sd;
}

TEST(McDropout, WithoutDropoutItIsThePlainPassAndDrawsNothing) {
  const MlpOptions o = tanh_net({5, 4}, 1.0, DropoutPlacement::between_hidden);
  const Net net(o, 1);
  const Mlp& mlp = net.mlp;
  const Eigen::VectorXd& p = net.p;
  EXPECT_FALSE(mlp.has_any_dropout());
  const Eigen::MatrixXd x = random_inputs(3, 6, 2);
  Rng rng(7), untouched(7);
  EXPECT_EQ(mlp.predict_mc(p, x, 10, rng), mlp.predict(p, x));
  EXPECT_EQ(rng.next_u64(), untouched.next_u64());
  // Seed 000's placement with one hidden layer drops nothing either.
  EXPECT_FALSE(Mlp(tanh_net({5}, 0.5, DropoutPlacement::between_hidden)).has_any_dropout());
}

TEST(McDropout, InferFollowsTheInferenceAndItsSampleCount) {
  MlpOptions o = tanh_net({5, 4}, 0.7, DropoutPlacement::between_hidden);
  o.dropout_mc_samples = 17;
  const Net net(o, 1);
  const Mlp& mlp = net.mlp;
  const Eigen::VectorXd& p = net.p;
  const Eigen::MatrixXd x = random_inputs(3, 8, 2);
  Rng a(4), b(4);
  EXPECT_EQ(mlp.infer(p, x, DropoutInference::deterministic, a), mlp.predict(p, x));
  EXPECT_EQ(mlp.infer(p, x, DropoutInference::mc, a), mlp.predict_mc(p, x, 17, b));
}

TEST(McDropout, SampleCountValidated) {
  MlpOptions o = tanh_net({4}, 0.5, DropoutPlacement::between_hidden);
  o.dropout_mc_samples = 0;
  EXPECT_THROW(o.validate(), OptionError);
  o.dropout_mc_samples = 1000001;
  EXPECT_THROW(o.validate(), OptionError);
  o.dropout_mc_samples = 1;
  EXPECT_NO_THROW(o.validate());
}

}  // namespace
}  // namespace cnclab
