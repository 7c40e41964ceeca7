// The exact sparse Jacobian and Hessian of the feedrate NLP against central
// finite differences of its constraint values (Ceres' gradient-checker idea).
#include "cnclab/motion/feedrate_nlp.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <vector>

#include "cnclab/core/rng.hpp"

namespace cnclab::feedrate_detail {
namespace {

constexpr double kStep = 1e-6;
constexpr double kTolerance = 1e-6;  // relative to max(1, |entry|)

struct Problem {
  Ipopt::SmartPtr<FeedrateNlp> nlp;
  int n = 0, m = 0, nnz_jac = 0, nnz_h = 0;
};

Problem random_problem(Rng& rng, int intervals) {
  std::vector<NodeCoefficients> nodes(intervals + 1);
  double w = 0.0;
  for (auto& c : nodes) {
    for (int i = 0; i < 2; ++i) {
      c.vel[i] = rng.uniform(-1, 1);
      c.acc1[i] = rng.uniform(-1, 1);
      c.acc2[i] = rng.uniform(-1, 1);
      c.jerk1[i] = rng.uniform(-1, 1);
      c.jerk2[i] = rng.uniform(-1, 1);
      c.jerk3[i] = rng.uniform(-1, 1);
    }
    c.w = w;
    w += rng.uniform(0.1, 0.3);
  }
  Problem p;
  p.nlp = new FeedrateNlp(nodes, {0.5, 0.1}, std::vector<double>(4 * intervals + 2, 0.0));
  Ipopt::TNLP::IndexStyleEnum style;
  p.nlp->get_nlp_info(p.n, p.m, p.nnz_jac, p.nnz_h, style);
  return p;
}

Eigen::VectorXd constraints(Problem& p, const Eigen::VectorXd& x) {
  Eigen::VectorXd g(p.m);
  p.nlp->eval_g(p.n, x.data(), true, p.m, g.data());
  return g;
}

Eigen::MatrixXd dense_jacobian(Problem& p, const Eigen::VectorXd& x) {
  std::vector<Ipopt::Index> rows(p.nnz_jac), cols(p.nnz_jac);
  std::vector<double> values(p.nnz_jac);
  p.nlp->eval_jac_g(p.n, nullptr, true, p.m, p.nnz_jac, rows.data(), cols.data(), nullptr);
  p.nlp->eval_jac_g(p.n, x.data(), true, p.m, p.nnz_jac, nullptr, nullptr, values.data());
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(p.m, p.n);
  for (int e = 0; e < p.nnz_jac; ++e) J(rows[e], cols[e]) += values[e];
  return J;
}

TEST(FeedrateNlp, JacobianMatchesFiniteDifferences) {
  Rng rng(21);
  Problem p = random_problem(rng, 5);
  Eigen::VectorXd x(p.n);
  for (int i = 0; i < p.n; ++i) x[i] = rng.uniform(0.2, 1.5);
  const Eigen::MatrixXd J = dense_jacobian(p, x);
  for (int j = 0; j < p.n; ++j) {
    Eigen::VectorXd xp = x, xm = x;
    xp[j] += kStep;
    xm[j] -= kStep;
    const Eigen::VectorXd fd = (constraints(p, xp) - constraints(p, xm)) / (2 * kStep);
    for (int r = 0; r < p.m; ++r) {
      EXPECT_NEAR(J(r, j), fd[r], kTolerance * std::max(1.0, std::abs(fd[r])))
          << "row " << r << " variable " << j;
    }
  }
}

TEST(FeedrateNlp, HessianOfTheLagrangianMatchesFiniteDifferences) {
  Rng rng(22);
  Problem p = random_problem(rng, 5);
  Eigen::VectorXd x(p.n), lambda(p.m);
  for (int i = 0; i < p.n; ++i) x[i] = rng.uniform(0.2, 1.5);
  for (int r = 0; r < p.m; ++r) lambda[r] = rng.uniform(-1, 1);
  const double obj_factor = 0.7;  // the objective is linear: no contribution
  std::vector<Ipopt::Index> rows(p.nnz_h), cols(p.nnz_h);
  std::vector<double> values(p.nnz_h);
  p.nlp->eval_h(p.n, nullptr, true, obj_factor, p.m, nullptr, true, p.nnz_h, rows.data(),
                cols.data(), nullptr);
  p.nlp->eval_h(p.n, x.data(), true, obj_factor, p.m, lambda.data(), true, p.nnz_h, nullptr,
                nullptr, values.data());
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(p.n, p.n);
  for (int e = 0; e < p.nnz_h; ++e) {
    ASSERT_GE(rows[e], cols[e]) << "lower triangle only";
    H(rows[e], cols[e]) += values[e];
    if (rows[e] != cols[e]) H(cols[e], rows[e]) += values[e];
  }
  // d/dx_j of grad L = J^T lambda (+ obj_factor * grad f, constant).
  for (int j = 0; j < p.n; ++j) {
    Eigen::VectorXd xp = x, xm = x;
    xp[j] += kStep;
    xm[j] -= kStep;
    const Eigen::VectorXd fd =
        (dense_jacobian(p, xp).transpose() * lambda - dense_jacobian(p, xm).transpose() * lambda) /
        (2 * kStep);
    for (int i = 0; i < p.n; ++i) {
      EXPECT_NEAR(H(i, j), fd[i], kTolerance * std::max(1.0, std::abs(fd[i])))
          << "entry (" << i << ", " << j << ")";
    }
  }
}

}  // namespace
}  // namespace cnclab::feedrate_detail
