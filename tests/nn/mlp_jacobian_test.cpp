// Mlp::output_jacobian against central finite differences of predict(), and
// against the mean-squared-error gradient (2/n J^T (y - t), an identity).
#include <gtest/gtest.h>

#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/nn/mlp.hpp"

namespace cnclab {
namespace {

// Central differences, h = 1e-6 on O(1) values: error ~1e-10 (see mlp_test).
constexpr double kJacobianFdStep = 1e-6;
constexpr double kJacTol = 1e-6;

struct Case {
  Activation hidden, output;
  std::vector<std::size_t> widths;
  std::size_t in, out;
};

void check_jacobian(const Case& c, std::uint64_t seed) {
  MlpOptions o;
  o.inputs = c.in;
  o.outputs = c.out;
  o.hidden = c.widths;
  o.hidden_activation = c.hidden;
  o.output_activation = c.output;
  o.weights = {Initializer::Kind::normal, 0.0, 0.5};
  const Mlp mlp(o);
  Rng rng(seed);
  Eigen::VectorXd p;
  mlp.initialise(p, rng);
  const Eigen::Index batch = 4, n_out = static_cast<Eigen::Index>(c.out);
  Eigen::MatrixXd x(o.inputs, batch);
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = rng.normal();
  Mlp::Workspace ws;
  Eigen::MatrixXd y(n_out, batch), jac(batch * n_out, p.size());
  mlp.output_jacobian(p, x, ws, y, jac);
  EXPECT_TRUE(y.isApprox(mlp.predict(p, x), 1e-14));
  for (Eigen::Index k = 0; k < p.size(); ++k) {
    Eigen::VectorXd plus = p, minus = p;
    plus[k] += kJacobianFdStep;
    minus[k] -= kJacobianFdStep;
    const Eigen::MatrixXd fd =
        (mlp.predict(plus, x) - mlp.predict(minus, x)) / (2 * kJacobianFdStep);
    for (Eigen::Index s = 0; s < batch; ++s) {
      for (Eigen::Index j = 0; j < n_out; ++j) {
        ASSERT_NEAR(jac(s * n_out + j, k), fd(j, s), kJacTol * std::max(1.0, std::abs(fd(j, s))))
            << "sample " << s << ", output " << j << ", parameter " << k;
      }
    }
  }
  // Identity: MSE gradient = 2 / (n_out batch) J^T (y - t).
  Eigen::MatrixXd t(n_out, batch);
  for (Eigen::Index i = 0; i < t.size(); ++i) t.data()[i] = rng.normal();
  Eigen::VectorXd g;
  mlp.prepare(ws, batch);
  mlp.loss_and_gradient(p, x, t, ws, g);
  const Eigen::MatrixXd r = y - t;
  const Eigen::VectorXd jt =
      jac.transpose() * Eigen::Map<const Eigen::VectorXd>(r.data(), r.size());
  EXPECT_TRUE(g.isApprox(2.0 / static_cast<double>(r.size()) * jt, 1e-12));
}

TEST(MlpJacobian, MatchesFiniteDifferencesForEveryActivation) {
  for (Activation a :
       {Activation::relu, Activation::tanh, Activation::sigmoid, Activation::linear}) {
    SCOPED_TRACE(to_string(a));
    check_jacobian({a, Activation::linear, {6, 4}, 3, 2}, 21);
    check_jacobian({Activation::tanh, a, {5}, 4, 3}, 22);
    check_jacobian({a, a, {}, 3, 1}, 23);  // no hidden layer
  }
}

TEST(MlpJacobian, RejectsWrongSizes) {
  MlpOptions o;
  o.inputs = 2;
  o.hidden = {3};
  const Mlp mlp(o);
  Eigen::VectorXd p = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(mlp.num_parameters()));
  Mlp::Workspace ws;
  Eigen::MatrixXd x(2, 3), y(1, 3), jac(2, p.size());
  EXPECT_THROW(mlp.output_jacobian(p, x, ws, y, jac), Error);
}

}  // namespace
}  // namespace cnclab
