// The damped Gauss-Newton step (train/gauss_newton.hpp) in its primal and
// dual forms and the shifted Gram decompositions (train/shifted_gram.hpp),
// against dense solves and eigenvalues of the explicit matrices (Eigen's
// LDLT and SelfAdjointEigenSolver), and the two forms against each other on
// whole lm and trainbr runs: NIST StRD data with N = P (the one shape where
// both forms apply to a certified problem), an over-parameterised network
// (N < P), and the closed-form evidence fixed point of a linear model with
// fewer samples than weights. "Agree" is 1e-9 relative throughout.
#include "cnclab/train/gauss_newton.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/train/lm.hpp"
#include "cnclab/train/mlp_residuals.hpp"
#include "cnclab/train/trainbr.hpp"
#include "random_matrix.hpp"

namespace cnclab {
namespace {

constexpr double kAgree = 1e-9;

using test::random_matrix;

double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).norm() / std::max(a.norm(), b.norm());
}

// e = A w - t.
class Linear : public ResidualObjective {
 public:
  Linear(Eigen::MatrixXd a, Eigen::VectorXd t) : a_(std::move(a)), t_(std::move(t)) {}
  Eigen::Index num_residuals() const override { return a_.rows(); }
  Eigen::Index num_parameters() const override { return a_.cols(); }
  void evaluate(const Eigen::VectorXd& w, Eigen::Index first, Eigen::Index count,
                Eigen::Ref<Eigen::VectorXd> e, Eigen::MatrixXd* jacobian) override {
    e = a_.middleRows(first, count) * w - t_.segment(first, count);
    if (jacobian) *jacobian = a_.middleRows(first, count);
  }

 private:
  Eigen::MatrixXd a_;
  Eigen::VectorXd t_;
};

double eigenvalue_count(const Eigen::MatrixXd& gram, double a, double b) {
  const Eigen::ArrayXd l =
      b * Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(gram).eigenvalues().array().cwiseMax(0.0);
  return (l / (l + a)).sum();
}

TEST(ShiftedGram, BothMethodsSolveEveryShiftAndCountLikeTheDenseMatrix) {
  Rng rng(11);
  // Full rank (60 x 40) and rank-deficient (20 x 40: 20 zero eigenvalues).
  for (const Eigen::Index rows : {60, 20}) {
    const Eigen::MatrixXd a = random_matrix(rows, 40, rng);
    const Eigen::MatrixXd gram = a.transpose() * a;
    const Eigen::VectorXd r = random_matrix(40, 1, rng);
    for (const auto method : {ShiftedGram::Method::spectral, ShiftedGram::Method::cholesky}) {
      ShiftedGram g;
      Eigen::MatrixXd lower = gram;
      lower.triangularView<Eigen::StrictlyUpper>().setConstant(std::nan(""));  // never read
      ASSERT_TRUE(g.reset(lower, method));
      for (const double b : {0.5, 2.5}) {
        for (const double c : {1e-3, 0.3, 1e3}) {
          Eigen::MatrixXd m = b * gram;
          m.diagonal().array() += c;
          const Eigen::VectorXd ref = m.ldlt().solve(r);
          Eigen::VectorXd x;
          ASSERT_TRUE(g.solve(b, c, r, x));
          EXPECT_LE(relative_difference(x, ref), kAgree) << rows << " rows, b " << b << ", c " << c;
          const double count = g.effective_count(c, b), want = eigenvalue_count(gram, c, b);
          EXPECT_NEAR(count, want, kAgree * want) << rows << " rows, b " << b << ", c " << c;
        }
      }
    }
  }
}

TEST(ShiftedGram, NonFiniteGramMatrixIsRefused) {
  Eigen::MatrixXd gram = Eigen::MatrixXd::Identity(3, 3);
  gram(2, 1) = std::nan("");
  ShiftedGram g;
  EXPECT_FALSE(g.reset(gram, ShiftedGram::Method::spectral));
}

// dw = -(beta J^T J + (mu + alpha) I)^-1 (beta J^T e + alpha w) from the
// thin SVD J = U S V^T (V: P x r): on the range of V the matrix is
// diag(beta s_i^2 + c), on its complement c I, and the right-hand side's
// part there is alpha (I - V V^T) w (J^T e has none). Accurate to rounding
// however small mu is (a dense solve of the damped matrix loses
// cond = ||J||^2 / mu of it).
Eigen::VectorXd svd_step(const Eigen::MatrixXd& j, const Eigen::VectorXd& e,
                         const Eigen::VectorXd& w, double alpha, double beta, double mu) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(j, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::MatrixXd &u = svd.matrixU(), &v = svd.matrixV();
  const Eigen::ArrayXd s = svd.singularValues().array();
  const double c = mu + alpha;
  const Eigen::VectorXd vw = v.transpose() * w;
  const Eigen::ArrayXd range =
      (beta * s * (u.transpose() * e).array() + alpha * vw.array()) / (beta * s.square() + c);
  return -(v * range.matrix() + (alpha / c) * (w - v * vw));
}

TEST(DampedGaussNewton, PrimalAndDualStepsEqualTheDenseSolveWhenNIsBelowP) {
  Rng rng(12);
  const Eigen::Index n = 15, p = 40;
  const Eigen::MatrixXd a = random_matrix(n, p, rng);
  const Eigen::VectorXd t = random_matrix(n, 1, rng), w = random_matrix(p, 1, rng);
  const Eigen::VectorXd e = a * w - t;
  Linear objective(a, t);
  DampedGaussNewton automatic(objective, LmForm::automatic, LmDecomposition::automatic);
  EXPECT_EQ(automatic.form(), LmForm::dual);  // N < P
  for (const LmForm form : {LmForm::primal, LmForm::dual}) {
    for (const auto d : {LmDecomposition::spectral, LmDecomposition::cholesky}) {
      DampedGaussNewton system(objective, form, d);
      ASSERT_TRUE(system.build(w));
      EXPECT_NEAR(system.sse(), e.squaredNorm(), 1e-13 * e.squaredNorm());
      EXPECT_LE(relative_difference(system.jte(), a.transpose() * e), 1e-13);
      EXPECT_NEAR(system.max_jtj_diagonal(), (a.transpose() * a).diagonal().maxCoeff(), 1e-12);
      // lm (alpha 0, beta 1) and trainbr-like dampings, mu from tiny to large.
      for (const auto& [alpha, beta] : {std::pair{0.0, 1.0}, {0.05, 3.0}, {2.0, 0.4}}) {
        for (const double mu : {1e-8, 1e-3, 10.0}) {
          Eigen::VectorXd dw;
          ASSERT_TRUE(system.step(alpha, beta, mu, w, dw));
          // The dual to 1e-9 at every damping. The primal's P x P matrix is
          // singular but for the damping when N < P: it is backward stable,
          // so within P eps cond(beta J^T J + c I) (shifted_gram.hpp), 1e-9
          // unless mu + alpha is tiny (lm's mu = 1e-8 here: cond ~ 1e10,
          // the reason the dual is the automatic form for N < P).
          const double c = mu + alpha;
          const double cond = (beta * (a.transpose() * a).diagonal().sum() + c) / c;
          const double bound =
              form == LmForm::dual
                  ? kAgree
                  : std::max(kAgree, static_cast<double>(p) *
                                         std::numeric_limits<double>::epsilon() * cond);
          EXPECT_LE(relative_difference(dw, svd_step(a, e, w, alpha, beta, mu)), bound)
              << (form == LmForm::dual ? "dual" : "primal") << " alpha " << alpha << " mu " << mu;
        }
        if (alpha > 0) {
          const double want = eigenvalue_count(a.transpose() * a, alpha, beta);
          EXPECT_NEAR(system.effective_parameters(alpha, beta), want, kAgree * want);
        }
      }
    }
  }
}

TEST(DampedGaussNewton, ForcedDualNeedsNoMoreResidualsThanParameters) {
  Rng rng(13);
  Linear tall(random_matrix(10, 4, rng), random_matrix(10, 1, rng));
  try {
    DampedGaussNewton system(tall, LmForm::dual, LmDecomposition::automatic);
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_NE(std::string(e.what()).find("form"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("10 residuals, 4 parameters"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(DampedGaussNewton(tall, LmForm::automatic, LmDecomposition::automatic).form(),
            LmForm::primal);
}

// NIST StRD Thurber (y = (b1 + b2 x + b3 x^2 + b4 x^3) / (1 + b5 x + b6 x^2
// + b7 x^3)) on every 6th of its 37 observations (7, spread over the range)
// from NIST's start 1: N = P = 7, an interpolation both forms can solve.
class ThurberHead : public ResidualObjective {
 public:
  ThurberHead() {
    const std::string path = std::string(CNCLAB_SOURCE_DIR) + "/tests/train/data/nist/thurber.txt";
    std::ifstream file(path);
    EXPECT_TRUE(file) << path;
    int row = 0;
    for (std::string line; std::getline(file, line);) {
      if (line.empty() || line[0] == '#' || std::isalpha(static_cast<unsigned char>(line[0])))
        continue;
      if (row++ % 6 != 0) continue;
      std::istringstream in(line);
      double y = 0, x = 0;
      in >> y >> x;
      y_.push_back(y);
      x_.push_back(x);
    }
  }
  Eigen::Index num_residuals() const override { return static_cast<Eigen::Index>(x_.size()); }
  Eigen::Index num_parameters() const override { return 7; }
  void evaluate(const Eigen::VectorXd& b, Eigen::Index first, Eigen::Index count,
                Eigen::Ref<Eigen::VectorXd> e, Eigen::MatrixXd* jacobian) override {
    for (Eigen::Index r = 0; r < count; ++r) {
      const double x = x_[static_cast<std::size_t>(first + r)];
      const double num = b[0] + x * (b[1] + x * (b[2] + x * b[3]));
      const double den = 1 + x * (b[4] + x * (b[5] + x * b[6]));
      e[r] = num / den - y_[static_cast<std::size_t>(first + r)];
      if (!jacobian) continue;
      double xp = 1;
      for (int j = 0; j < 4; ++j, xp *= x) (*jacobian)(r, j) = xp / den;
      xp = x;
      for (int j = 4; j < 7; ++j, xp *= x) (*jacobian)(r, j) = -num * xp / (den * den);
    }
  }

 private:
  std::vector<double> x_, y_;
};

TEST(DampedGaussNewton, FormsAgreeOnNistThurberWithAsManyObservationsAsParameters) {
  Eigen::VectorXd start(7);
  start << 1000, 1000, 400, 40, 0.7, 0.3, 0.03;  // NIST start 1
  Eigen::VectorXd by_form[2];
  double sse[2] = {0, 0};
  for (const LmForm form : {LmForm::primal, LmForm::dual}) {
    ThurberHead objective;
    ASSERT_EQ(objective.num_residuals(), 7);
    Eigen::VectorXd b = start;
    LmOptions o;
    o.form = form;
    o.epochs = 200;
    const Summary s = train_lm(objective, b, o);
    ASSERT_NE(s.termination, Termination::diverged) << s.message;
    const int i = form == LmForm::dual ? 1 : 0;
    by_form[i] = b;
    sse[i] = s.lm_history.back().sse;
  }
  EXPECT_LE(relative_difference(by_form[0], by_form[1]), kAgree) << by_form[0].transpose() << "\n"
                                                                 << by_form[1].transpose();
  EXPECT_LT(sse[0], 1e-12 * 7 * 1500 * 1500);  // an interpolation: SSE at rounding level
  EXPECT_LT(sse[1], 1e-12 * 7 * 1500 * 1500);
}

TEST(DampedGaussNewton, FormsAgreeOnAWholeTrainbrRunOfAnOverparameterisedNetwork) {
  // 6-12-1 tanh: 97 weights, 40 samples.
  Rng rng(14);
  const Eigen::MatrixXd x = random_matrix(6, 40, rng);
  Eigen::MatrixXd y(1, 40);
  for (Eigen::Index s = 0; s < 40; ++s) y(0, s) = std::sin(x(0, s)) + 0.3 * x(1, s) * x(2, s);
  MlpOptions mo;
  mo.inputs = 6;
  mo.hidden = {12};
  mo.outputs = 1;
  mo.hidden_activation = Activation::tanh;
  mo.weights = {Initializer::Kind::xavier};
  const Mlp mlp(mo);
  Eigen::VectorXd w0;
  mlp.initialise(w0, rng);
  ASSERT_GT(w0.size(), 40);
  for (const bool bayesian : {false, true}) {
    Eigen::VectorXd by_form[2];
    Summary summaries[2];
    for (const LmForm form : {LmForm::primal, LmForm::dual}) {
      MlpResidualObjective objective(mlp, x, y);
      Eigen::VectorXd w = w0;
      TrainbrOptions o;
      o.form = form;
      // lm interpolates the 40 samples within a few epochs and then works at
      // the rounding floor, where no two orders of sums agree: 6 epochs.
      o.epochs = bayesian ? 40 : 6;
      o.min_gradient = 0;
      const int i = form == LmForm::dual ? 1 : 0;
      summaries[i] = bayesian ? train_trainbr(objective, w, o) : train_lm(objective, w, o);
      ASSERT_NE(summaries[i].termination, Termination::diverged) << summaries[i].message;
      by_form[i] = w;
    }
    const std::string what = bayesian ? "trainbr" : "lm";
    ASSERT_EQ(summaries[0].lm_history.size(), summaries[1].lm_history.size()) << what;
    EXPECT_LE(relative_difference(by_form[0], by_form[1]), kAgree) << what;
    const LmEpochRecord &p = summaries[0].lm_history.back(), &d = summaries[1].lm_history.back();
    // E_D to 1e-9 of the data's scale (lm nearly interpolates: E_D itself
    // is a small difference of large terms).
    EXPECT_NEAR(p.sse, d.sse, kAgree * (p.sse + y.squaredNorm())) << what;
    EXPECT_NEAR(p.gamma, d.gamma, kAgree * p.gamma) << what;
    EXPECT_NEAR(p.alpha, d.alpha, kAgree * std::abs(p.alpha)) << what;
    EXPECT_NEAR(p.beta, d.beta, kAgree * p.beta) << what;
    if (bayesian) {
      EXPECT_LT(p.gamma, 40.0) << "gamma <= rank J <= N";
    }
  }
}

}  // namespace
}  // namespace cnclab
