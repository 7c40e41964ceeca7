// lm and trainbr beyond the NIST problems: the blocked normal equations
// against J built whole, the Bayesian fixed point on a linear model against
// the closed-form evidence maximisation, regularisation on an over-sized
// network, failure handling and option validation.
#include "cnclab/train/lm.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/nn/minmax.hpp"
#include "cnclab/train/mlp_residuals.hpp"
#include "cnclab/train/normal_equations.hpp"
#include "cnclab/train/trainbr.hpp"
#include "random_matrix.hpp"

namespace cnclab {
namespace {

using test::random_matrix;

// e = A w - t: a linear residual with a known Jacobian A.
class LinearResiduals : public ResidualObjective {
 public:
  LinearResiduals(Eigen::MatrixXd a, Eigen::VectorXd t) : a_(std::move(a)), t_(std::move(t)) {}
  Eigen::Index num_residuals() const override { return a_.rows(); }
  Eigen::Index num_parameters() const override { return a_.cols(); }
  void evaluate(const Eigen::VectorXd& w, Eigen::Index first, Eigen::Index count,
                Eigen::Ref<Eigen::VectorXd> e, Eigen::MatrixXd* jacobian) override {
    ++evaluations;
    e = a_.middleRows(first, count) * w - t_.segment(first, count);
    if (poison_after >= 0 && evaluations > poison_after) e[0] = std::nan("");
    if (jacobian) *jacobian = a_.middleRows(first, count);
  }
  int evaluations = 0;
  int poison_after = -1;  // residuals become NaN after this many evaluations (-1: never)

 private:
  Eigen::MatrixXd a_;
  Eigen::VectorXd t_;
};

TEST(NormalEquations, BlockedRankUpdatesEqualTheWholeJacobian) {
  Rng rng(1);
  const Eigen::MatrixXd a = random_matrix(103, 7, rng);
  const Eigen::VectorXd t = random_matrix(103, 1, rng);
  const Eigen::VectorXd w = random_matrix(7, 1, rng);
  const Eigen::VectorXd e = a * w - t;
  const Eigen::MatrixXd jtj = a.transpose() * a;
  for (Eigen::Index block : {1, 10, 64, 103, 500}) {
    LinearResiduals r(a, t);
    NormalEquationBuilder builder(r, block);
    NormalEquations ne;
    ASSERT_TRUE(builder.build(w, ne));
    const Eigen::MatrixXd full = ne.jtj.selfadjointView<Eigen::Lower>();
    EXPECT_TRUE(full.isApprox(jtj, 1e-13)) << "block " << block;
    EXPECT_TRUE(ne.jte.isApprox(a.transpose() * e, 1e-13));
    EXPECT_NEAR(ne.sse, e.squaredNorm(), 1e-12 * e.squaredNorm());
    EXPECT_NEAR(builder.sum_of_squares(w), e.squaredNorm(), 1e-12 * e.squaredNorm());
  }
}

TEST(Lm, LinearLeastSquaresMatchesQrAndStopsOnGradient) {
  Rng rng(2);
  const Eigen::MatrixXd a = random_matrix(50, 4, rng);
  const Eigen::VectorXd t = random_matrix(50, 1, rng);
  LinearResiduals r(a, t);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(4);
  LmOptions o;
  o.min_gradient = 1e-9;
  const Summary s = train_lm(r, w, o);
  EXPECT_EQ(s.termination, Termination::min_gradient) << s.message;
  const Eigen::VectorXd ref = a.colPivHouseholderQr().solve(t);
  EXPECT_TRUE(w.isApprox(ref, 1e-9));
  // History: SSE never increases, mu follows the x0.1 schedule on success.
  ASSERT_FALSE(s.lm_history.empty());
  EXPECT_NEAR(s.lm_history.front().mu, o.mu * o.mu_dec, 1e-18);
  for (std::size_t i = 1; i < s.lm_history.size(); ++i) {
    EXPECT_LE(s.lm_history[i].sse, s.lm_history[i - 1].sse);
    EXPECT_EQ(s.lm_history[i].alpha, 0.0);
  }
}

TEST(Lm, GoalAndEpochLimitStop) {
  Rng rng(3);
  const Eigen::MatrixXd a = random_matrix(30, 3, rng);
  const Eigen::VectorXd t = a * Eigen::Vector3d(1, -2, 3);  // exact fit: SSE -> 0
  LinearResiduals r(a, t);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(3);
  LmOptions o;
  o.goal = 1e-6;
  EXPECT_EQ(train_lm(r, w, o).termination, Termination::goal);
  w.setZero();
  o.goal = 0;
  o.min_gradient = 0;
  o.epochs = 1;
  const Summary s = train_lm(r, w, o);
  EXPECT_EQ(s.termination, Termination::max_epochs);
  EXPECT_EQ(s.history.size(), 1u);
}

TEST(Lm, GradientAndGoalAreMatlabsMsePerformanceTrainbrsSse) {
  // trainlm (default performance mse): performance E_D / N, gradient
  // 2 ||J^T e|| / N; trainbr (sse): E_D and 2 ||J^T e||. Checked with the
  // linear residual's own Jacobian A at the returned weights.
  Rng rng(6);
  const Eigen::MatrixXd a = random_matrix(200, 3, rng);
  const Eigen::VectorXd t = random_matrix(200, 1, rng);
  const double n = 200;
  const auto gradient = [&](const Eigen::VectorXd& w) {
    return 2 * (a.transpose() * (a * w - t)).norm();
  };
  LinearResiduals r(a, t);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(3);
  LmOptions o;
  o.min_gradient = 1e-6;  // on the mse gradient: the sse gradient may be up to 200x larger
  Summary s = train_lm(r, w, o);
  ASSERT_EQ(s.termination, Termination::min_gradient) << s.message;
  EXPECT_LE(gradient(w) / n, 1e-6);
  EXPECT_NEAR(s.lm_history.back().gradient, gradient(w) / n, 1e-12);
  // trainbr's data-term gradient does not vanish at its regularised optimum
  // (beta J^T e = -alpha w), so compare the recorded value only.
  TrainbrOptions b;
  b.epochs = 5;
  w.setZero();
  s = train_trainbr(r, w, b);
  ASSERT_EQ(s.termination, Termination::max_epochs) << s.message;
  EXPECT_NEAR(s.lm_history.back().gradient, gradient(w), 1e-9 * gradient(w));
  // goal: lm on the mean, trainbr on the sum of squared errors.
  const Eigen::VectorXd exact = a * Eigen::Vector3d(1, 2, 3) + 0.1 * t;  // mse ~ 0.01
  LinearResiduals near(a, exact);
  o = {};
  o.goal = 0.02;  // above the best mse: met; the sum (~2) is not
  w.setZero();
  s = train_lm(near, w, o);
  EXPECT_EQ(s.termination, Termination::goal) << s.message;
  EXPECT_LE((a * w - exact).squaredNorm() / n, 0.02);
  b = {};
  b.goal = 0.02;
  w.setZero();
  EXPECT_NE(train_trainbr(near, w, b).termination, Termination::goal);
}

TEST(Termination, EveryValueRoundTrips) {
  for (int i = 0; i <= static_cast<int>(Termination::mu_max); ++i) {
    const auto t = static_cast<Termination>(i);
    Termination parsed = Termination::goal;
    ASSERT_TRUE(parse_termination(to_string(t), parsed)) << i << " " << to_string(t);
    EXPECT_EQ(parsed, t);
  }
  Termination untouched = Termination::goal;
  EXPECT_FALSE(parse_termination("converged", untouched));
  EXPECT_EQ(untouched, Termination::goal);
}

TEST(Lm, RecordsTheInitialStateAndTheCurvatureScale) {
  // Linear residuals A w - t: J = A, so the curvature scale is
  // beta max_i (A^T A)_ii = beta max_i ||A_:,i||^2; before the first step
  // (w = 0) E_D = ||t||^2, E_W = 0, and trainbr's beta = (N - N_w) / (2 E_D),
  // alpha = 1 (E_W = 0; trainbr.hpp).
  Rng rng(7);
  Eigen::MatrixXd a = random_matrix(50, 3, rng);
  a.col(1) *= 10;  // the largest column
  const Eigen::VectorXd t = random_matrix(50, 1, rng);
  LinearResiduals r(a, t);
  const double max_diag = a.colwise().squaredNorm().maxCoeff();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(3);
  LmOptions o;
  o.epochs = 2;
  const Summary lm = train_lm(r, w, o);
  ASSERT_TRUE(lm.lm_initial);
  EXPECT_NEAR(lm.lm_initial->sse, t.squaredNorm(), 1e-12 * t.squaredNorm());
  EXPECT_EQ(lm.lm_initial->mu, o.mu);
  EXPECT_NEAR(lm.lm_initial->curvature, max_diag, 1e-12 * max_diag);
  EXPECT_NEAR(lm.lm_history.back().curvature, max_diag, 1e-12 * max_diag);
  w.setZero();
  TrainbrOptions b;
  b.epochs = 2;
  const Summary br = train_trainbr(r, w, b);
  ASSERT_TRUE(br.lm_initial);
  const double beta0 = (50.0 - 3.0) / (2 * t.squaredNorm());
  EXPECT_NEAR(br.lm_initial->beta, beta0, 1e-12 * beta0);
  EXPECT_EQ(br.lm_initial->alpha, 1.0);
  EXPECT_NEAR(br.lm_initial->curvature, beta0 * max_diag, 1e-12 * beta0 * max_diag);
  const LmEpochRecord& last = br.lm_history.back();
  EXPECT_NEAR(last.curvature, last.beta * max_diag, 1e-12 * last.beta * max_diag);
}

// A validation loss hook that replays `values`: the first for the starting
// parameters, then one per epoch (the last repeats).
LmHooks replayed_validation(std::vector<double> values, std::vector<Eigen::VectorXd>* params) {
  LmHooks hooks;
  auto calls = std::make_shared<std::size_t>(0);
  hooks.validation_loss = [values, calls](const Eigen::VectorXd&) {
    return values[std::min((*calls)++, values.size() - 1)];
  };
  hooks.on_epoch = [params](const EpochRecord&, const LmEpochRecord&, const Eigen::VectorXd& p) {
    params->push_back(p);
    return true;
  };
  return hooks;
}

TEST(Lm, ValidationStopAfterMaxFailReturnsTheBestEpoch) {
  // trainlm's max_fail: an epoch worse than the best is a failed check, an
  // equal one is not, a new best resets the count; the best epoch's
  // parameters are returned. A small sigmoid network trains for many epochs.
  Rng rng(7);
  Eigen::MatrixXd x(2, 60), y(1, 60);
  for (Eigen::Index s = 0; s < 60; ++s) {
    x.col(s) << rng.uniform(-1, 1), rng.uniform(-1, 1);
    y(0, s) = std::sin(3 * x(0, s)) * x(1, s);
  }
  MlpOptions mo;
  mo.inputs = 2;
  mo.hidden = {6};
  mo.outputs = 1;
  const Mlp mlp(mo);
  Eigen::VectorXd start;
  mlp.initialise(start, rng);
  MlpResidualObjective objective(mlp, x, y);
  LmOptions o;
  o.min_gradient = 0;
  o.epochs = 100;
  o.max_fail = 3;
  // Epochs 1..: 9, 8, 7 (best, epoch 3), 7 (equal: no fail), 7.5, NaN, 7.2 -> 3 fails.
  std::vector<Eigen::VectorXd> seen;
  Eigen::VectorXd w = start;
  Summary s =
      train_lm(objective, w, o, replayed_validation({10, 9, 8, 7, 7, 7.5, NAN, 7.2}, &seen));
  EXPECT_EQ(s.termination, Termination::early_stop) << s.message;
  ASSERT_EQ(seen.size(), 7u);
  EXPECT_EQ(w, seen[2]) << "the parameters of epoch 3";
  EXPECT_NE(s.message.find("epoch 3"), std::string::npos) << s.message;
  // max_fail 0, or trainbr (no validation stop): the epochs run out.
  for (const bool bayesian : {false, true}) {
    seen.clear();
    w = start;
    o.max_fail = 0;
    o.epochs = 10;
    TrainbrOptions b;
    b.min_gradient = 0;
    b.epochs = 10;
    const LmHooks hooks = replayed_validation({10, 9, 8, 7, 7.5, 7.6, 7.7, 7.8}, &seen);
    s = bayesian ? train_trainbr(objective, w, b, hooks) : train_lm(objective, w, o, hooks);
    EXPECT_EQ(s.termination, Termination::max_epochs) << s.message;
    EXPECT_EQ(w, seen.back());
  }
}

TEST(Lm, NonFiniteTrialStepsAreRejectedNotPropagated) {
  Rng rng(4);
  const Eigen::MatrixXd a = random_matrix(20, 2, rng);
  const Eigen::VectorXd t = random_matrix(20, 1, rng);
  LinearResiduals r(a, t);
  r.poison_after = 1;  // the initial evaluation is fine, every trial is NaN
  Eigen::VectorXd w = Eigen::VectorXd::Ones(2);
  const Summary s = train_lm(r, w, LmOptions{});
  EXPECT_EQ(s.termination, Termination::mu_max) << s.message;
  EXPECT_TRUE(w.isApprox(Eigen::VectorXd::Ones(2)));  // untouched
  Eigen::VectorXd nan_start = Eigen::VectorXd::Constant(2, std::nan(""));
  LinearResiduals clean(a, t);
  EXPECT_EQ(train_lm(clean, nan_start, LmOptions{}).termination, Termination::diverged);
}

TEST(Lm, SingularJacobianIsHandledByTheDamping) {
  // Two identical columns: J^T J is singular, J^T J + mu I is not.
  Rng rng(5);
  Eigen::MatrixXd a = random_matrix(40, 3, rng);
  a.col(2) = a.col(1);
  const Eigen::VectorXd t = random_matrix(40, 1, rng);
  LinearResiduals r(a, t);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(3);
  const Summary s = train_lm(r, w, LmOptions{});
  EXPECT_NE(s.termination, Termination::diverged);
  EXPECT_TRUE(w.allFinite());
  // The fitted values equal the least-squares fit (unique even though w is not).
  const Eigen::VectorXd ref = a.colPivHouseholderQr().solve(t);
  EXPECT_TRUE((a * w).isApprox(a * ref, 1e-6));
}

TEST(Lm, OptionsValidatedWithFieldAndRule) {
  const auto message = [](auto mutate) {
    LmOptions o;
    mutate(o);
    try {
      o.validate();
    } catch (const OptionError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message([](LmOptions& o) { o.mu = -1; }), "mu = -1: must be a finite number > 0");
  EXPECT_EQ(message([](LmOptions& o) { o.mu = 1e11; }),
            "mu = 1e+11: must not exceed mu_max = 1e+10");
  EXPECT_EQ(message([](LmOptions& o) { o.mu_dec = 1; }), "mu_dec = 1: must be in (0, 1)");
  EXPECT_EQ(message([](LmOptions& o) { o.mu_inc = 0.5; }),
            "mu_inc = 0.5: must be a finite number > 1");
  EXPECT_EQ(message([](LmOptions& o) { o.epochs = 0; }), "epochs = 0: must be at least 1");
  EXPECT_EQ(message([](LmOptions& o) { o.min_gradient = std::nan(""); }),
            "min_gradient = nan: must be a finite number >= 0");
  EXPECT_EQ(message([](LmOptions& o) { o.goal = -1; }), "goal = -1: must be a finite number >= 0");
  EXPECT_EQ(message([](LmOptions&) {}), "no error");
  // MATLAB defaults.
  EXPECT_EQ(LmOptions{}.mu, 1e-3);
  EXPECT_EQ(TrainbrOptions{}.mu, 5e-3);
  EXPECT_EQ(TrainbrOptions{}.mu_max, 1e10);
  EXPECT_EQ(TrainbrOptions{}.epochs, 1000u);
}

TEST(Trainbr, EffectiveParametersFromTheCholeskyFactorMatchEigenvalues) {
  Rng rng(6);
  const Eigen::MatrixXd a = random_matrix(30, 6, rng);
  const Eigen::MatrixXd jtj = a.transpose() * a;
  const double alpha = 0.7, beta = 2.5;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(jtj);
  double gamma = 0;
  for (Eigen::Index i = 0; i < 6; ++i) {
    const double l = beta * eig.eigenvalues()[i];
    gamma += l / (l + alpha);
  }
  EXPECT_NEAR(effective_parameters(jtj, alpha, beta), gamma, 1e-12);
}

// Closed-form evidence maximisation for Bayesian linear regression (MacKay
// 1992, in the E_D = sum e^2, E_W = sum w^2 convention of trainbr.hpp), by
// iterating on the eigenvalues lambda_i of X^T X:
//   w = V diag(beta / (beta lambda_i + alpha)) V^T X^T t,
//   gamma = sum beta lambda_i / (beta lambda_i + alpha),
//   alpha = gamma / (2 |w|^2),  beta = (N - gamma) / (2 |X w - t|^2).
struct Evidence {
  double alpha, beta, gamma;
  Eigen::VectorXd w;
};
Evidence evidence_fixed_point(const Eigen::MatrixXd& x, const Eigen::VectorXd& t) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(x.transpose() * x);
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  const Eigen::VectorXd xt = eig.eigenvectors().transpose() * (x.transpose() * t);
  const double n = static_cast<double>(x.rows());
  Evidence ev{1.0, 1.0, 0.0, {}};
  for (int it = 0; it < 100000; ++it) {
    const Eigen::ArrayXd d = ev.beta / (ev.beta * lambda.array() + ev.alpha);
    ev.w = eig.eigenvectors() * (d * xt.array()).matrix();
    ev.gamma = (ev.beta * lambda.array() / (ev.beta * lambda.array() + ev.alpha)).sum();
    const double alpha = ev.gamma / (2 * ev.w.squaredNorm());
    const double beta = (n - ev.gamma) / (2 * (x * ev.w - t).squaredNorm());
    const bool done =
        std::abs(alpha - ev.alpha) <= 1e-15 * alpha && std::abs(beta - ev.beta) <= 1e-15 * beta;
    ev.alpha = alpha;
    ev.beta = beta;
    if (done) break;
  }
  return ev;
}

// A network with no hidden layer: y = W x + b, linear in its parameters,
// trained by trainbr in `form` on n samples of d inputs; the weights, alpha,
// beta and gamma must be the closed-form evidence maximum's. Weak signal and
// nuisance inputs, so that the prior matters (gamma clearly below N_w).
// With `prior_std` > 0 the true weights are drawn from N(0, prior_std^2)
// instead (the model trainbr assumes). Returns the trained parameters.
Eigen::VectorXd expect_closed_form_evidence(Eigen::Index n, Eigen::Index d, LmForm form,
                                            std::uint64_t seed = 7, double prior_std = 0) {
  Rng rng(seed);
  const Eigen::MatrixXd inputs = random_matrix(d, n, rng);
  Eigen::VectorXd true_w = Eigen::VectorXd::Zero(d);
  if (prior_std > 0) {
    true_w = prior_std * random_matrix(d, 1, rng);
  } else {
    true_w.head(3) << 0.8, -0.5, 0.05;
  }
  Eigen::MatrixXd targets(1, n);
  for (Eigen::Index s = 0; s < n; ++s)
    targets(0, s) = true_w.dot(inputs.col(s)) + 0.2 + rng.normal();

  MlpOptions mo;
  mo.inputs = static_cast<std::size_t>(d);
  mo.hidden = {};
  mo.outputs = 1;
  mo.output_activation = Activation::linear;
  const Mlp mlp(mo);
  Eigen::VectorXd params;
  mlp.initialise(params, rng);
  MlpResidualObjective objective(mlp, inputs, targets);
  TrainbrOptions o;
  o.min_gradient = 0;
  o.form = form;
  const Summary s = train_trainbr(objective, params, o);
  EXPECT_NE(s.termination, Termination::diverged) << s.message;

  // Independent: design matrix [x^T, 1] (parameter order W then b).
  Eigen::MatrixXd x(n, d + 1);
  x.leftCols(d) = inputs.transpose();
  x.col(d).setOnes();
  const Evidence ev = evidence_fixed_point(x, targets.row(0).transpose());
  const LmEpochRecord& last = s.lm_history.back();
  constexpr double kFixedPointTol = 1e-6;
  EXPECT_NEAR(last.alpha, ev.alpha, kFixedPointTol * ev.alpha);
  EXPECT_NEAR(last.beta, ev.beta, kFixedPointTol * ev.beta);
  EXPECT_NEAR(last.gamma, ev.gamma, kFixedPointTol * ev.gamma);
  EXPECT_TRUE(params.isApprox(ev.w, kFixedPointTol)) << params.transpose() << "\n"
                                                     << ev.w.transpose();
  EXPECT_LT(ev.gamma, static_cast<double>(std::min(n, d + 1)) - 0.5);  // the prior is active
  EXPECT_EQ(s.beta_guard_count, 0u);
  return params;
}

TEST(Trainbr, LinearModelReachesTheClosedFormEvidenceMaximum) {
  expect_closed_form_evidence(40, 6, LmForm::automatic);  // N > P: the primal form
}

TEST(Trainbr, BothFormsReachTheClosedFormEvidenceMaximumWithFewerSamplesThanWeights) {
  // 24 samples, 30 inputs + bias (the dual form by default, gauss_newton.hpp),
  // true weights from the prior. Both forms end within the fixed-point
  // tolerance above of the closed form, hence within twice it of each other:
  // trainbr's alternation of steps and re-estimates converges linearly, and
  // where each run stops (mu_max) decides the last digits, not the form. The
  // 1e-9 agreement of the forms' steps and gamma at one point is in
  // gauss_newton_test.cpp.
  const Eigen::VectorXd primal = expect_closed_form_evidence(24, 30, LmForm::primal, 1, 0.3);
  const Eigen::VectorXd dual = expect_closed_form_evidence(24, 30, LmForm::dual, 1, 0.3);
  EXPECT_LE((primal - dual).norm(), 2e-6 * primal.norm());
}

// Friedman #1 (Friedman 1991) with noise of std kNoise (signal std about 5).
constexpr double kNoise = 3.0;
void friedman1(Eigen::Index n, Rng& rng, Eigen::MatrixXd& x, Eigen::MatrixXd& y) {
  x.resize(10, n);
  y.resize(1, n);
  for (Eigen::Index s = 0; s < n; ++s) {
    for (Eigen::Index i = 0; i < 10; ++i) x(i, s) = rng.uniform();
    const auto c = x.col(s);
    y(0, s) = 10 * std::sin(std::numbers::pi * c[0] * c[1]) + 20 * (c[2] - 0.5) * (c[2] - 0.5) +
              10 * c[3] + 5 * c[4] + kNoise * rng.normal();
  }
}

TEST(Trainbr, RegularisesAnOversizedNetworkOnNoisyData) {
  Rng rng(8);
  Eigen::MatrixXd x_train, y_train, x_test, y_test;
  friedman1(200, rng, x_train, y_train);
  friedman1(1000, rng, x_test, y_test);
  MinMaxNormaliser sx, sy;
  sx.fit(x_train);
  sy.fit(y_train);
  const Eigen::MatrixXd xn = sx.transform(x_train), yn = sy.transform(y_train);
  const Eigen::MatrixXd xt = sx.transform(x_test), yt = sy.transform(y_test);

  MlpOptions mo;
  mo.inputs = 10;
  mo.hidden = {
      25};  // 301 parameters for 200 noisy samples  // 241 parameters for 400 noisy samples
  mo.outputs = 1;
  mo.hidden_activation = Activation::tanh;
  mo.weights = {Initializer::Kind::xavier};
  mo.biases = {Initializer::Kind::uniform, 0, 1, -0.1, 0.1};
  const Mlp mlp(mo);
  Eigen::VectorXd w0;
  mlp.initialise(w0, rng);
  const double nw = static_cast<double>(w0.size());

  Eigen::VectorXd w_lm = w0, w_br = w0;
  MlpResidualObjective lm_objective(mlp, xn, yn), br_objective(mlp, xn, yn);
  LmOptions lo;
  lo.epochs = 300;
  TrainbrOptions bo;
  bo.epochs = 300;
  const Summary lm = train_lm(lm_objective, w_lm, lo);
  const Summary br = train_trainbr(br_objective, w_br, bo);
  ASSERT_NE(lm.termination, Termination::diverged) << lm.message;
  ASSERT_NE(br.termination, Termination::diverged) << br.message;
  const auto test_mse = [&](const Eigen::VectorXd& w) {
    return (mlp.predict(w, xt) - yt).array().square().mean();
  };
  const double gamma = br.lm_history.back().gamma;
  EXPECT_LT(gamma, 0.5 * nw) << "gamma " << gamma << " of " << nw;
  EXPECT_GT(gamma, 1.0);
  EXPECT_LT(test_mse(w_br), test_mse(w_lm))
      << "trainbr " << test_mse(w_br) << ", lm " << test_mse(w_lm);
  // Unregularised LM fits the training noise: lower training error.
  EXPECT_LT(lm.lm_history.back().sse, br.lm_history.back().sse);
}

TEST(Trainbr, BetaGuardKeepsThePreviousBetaWhenGammaReachesN) {
  // J^T J = 1e20 I_3 with alpha = beta = 1: gamma = 3 - 3e-20, which is 3 in
  // double precision; with N = 3 residuals, N - gamma = 0.
  const Eigen::MatrixXd jtj = 1e20 * Eigen::MatrixXd::Identity(3, 3);
  const double gamma = effective_parameters(jtj, 1.0, 1.0);
  EXPECT_EQ(gamma, 3.0);
  BayesianHyperparameters h{1.0, 1.0, 3.0};
  EXPECT_FALSE(
      reestimate_hyperparameters(h, gamma, /*nw=*/3.0, /*sse=*/0.5, /*ssw=*/2.0, /*n=*/3.0));
  EXPECT_EQ(h.beta, 1.0);
  EXPECT_EQ(h.gamma, 3.0);
  EXPECT_NEAR(h.alpha, 3.0 / (2 * 2.0), 1e-15);
  // With N = 10 the update applies: beta = (10 - 3) / (2 * 0.5).
  h = {1.0, 1.0, 3.0};
  EXPECT_TRUE(reestimate_hyperparameters(h, gamma, 3.0, 0.5, 2.0, 10.0));
  EXPECT_NEAR(h.beta, 7.0, 1e-12);
  // E_D = 0 gives beta = 1 and E_W = 0 gives alpha = 1 (MATLAB).
  h = {0.5, 4.0, 3.0};
  EXPECT_TRUE(reestimate_hyperparameters(h, gamma, 3.0, 0.0, 0.0, 10.0));
  EXPECT_EQ(h.alpha, 1.0);
  EXPECT_EQ(h.beta, 1.0);
}

}  // namespace
}  // namespace cnclab
