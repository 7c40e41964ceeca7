#include "cnclab/train/sgdm.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

// f(w) = 1/2 sum_i a_i (w_i - c_i)^2 with one "sample": gradient a (w - c),
// minimum at c.
class Quadratic : public SeparableObjective {
 public:
  Quadratic(Eigen::VectorXd a, Eigen::VectorXd c) : a_(std::move(a)), c_(std::move(c)) {}
  std::size_t num_samples() const override { return 1; }
  std::size_t num_parameters() const override { return static_cast<std::size_t>(a_.size()); }
  double loss_and_gradient(const Eigen::VectorXd& w, std::span<const std::size_t>,
                           Eigen::VectorXd& g) override {
    g = a_.cwiseProduct(w - c_);
    return 0.5 * (a_.array() * (w - c_).array().square()).sum();
  }

 private:
  Eigen::VectorXd a_, c_;
};

// f(w) = 1/2 a (w - c)^2 in one dimension.
Quadratic scalar_quadratic(double a, double c) {
  return Quadratic(Eigen::VectorXd::Constant(1, a), Eigen::VectorXd::Constant(1, c));
}

TEST(Sgdm, StepsFollowEquation14ByHand) {
  Eigen::VectorXd a(2), c(2), w(2);
  a << 1, 4;
  c << 1, -1;
  w << 0, 0;
  Quadratic q(a, c);
  SgdmOptions o;
  o.learning_rate = 0.1;
  o.momentum = 0.5;
  o.epochs = 3;
  o.shuffle = false;
  Rng rng(1);
  Eigen::VectorXd trained = w;
  train_sgdm(q, trained, o, rng);
  // By hand: v <- 0.5 v - 0.1 a (w - c); w <- w + v, three times.
  Eigen::VectorXd v = Eigen::VectorXd::Zero(2), ref = w;
  for (int t = 0; t < 3; ++t) {
    v = 0.5 * v - 0.1 * a.cwiseProduct(ref - c).eval();
    ref += v;
  }
  EXPECT_NEAR((trained - ref).norm(), 0.0, 1e-15);
}

TEST(Sgdm, ZeroEpochsLeaveTheParametersBitIdentical) {
  Quadratic q = scalar_quadratic(2.0, 1.0);
  SgdmOptions o;
  o.epochs = 0;  // evaluation only
  Rng rng(1);
  Eigen::VectorXd w = Eigen::VectorXd::Constant(1, 0.1 + 0.2);
  const Summary s = train_sgdm(q, w, o, rng);
  EXPECT_EQ(w[0], 0.1 + 0.2);
  EXPECT_TRUE(s.history.empty());
  EXPECT_EQ(s.termination, Termination::max_epochs);
}

TEST(Sgdm, ConvergesToTheKnownOptimum) {
  Eigen::VectorXd a(3), c(3);
  a << 1, 2, 3;
  c << 0.5, -2, 3;
  Quadratic q(a, c);
  SgdmOptions o;
  o.learning_rate = 0.05;
  o.momentum = 0.9;
  o.epochs = 2000;
  Rng rng(2);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(3);
  const Summary s = train_sgdm(q, w, o, rng);
  EXPECT_EQ(s.termination, Termination::max_epochs);
  EXPECT_LT((w - c).norm(), 1e-10);
}

// Linear model y = W x + b with MSE: a network without hidden layers and a
// linear output. Full-batch SGDM must reach the least-squares solution found
// independently by QR.
TEST(Sgdm, LinearNetworkReachesLeastSquaresSolution) {
  Rng data_rng(3);
  constexpr Eigen::Index kN = 200;
  Eigen::MatrixXd x(3, kN), y(1, kN);
  for (Eigen::Index j = 0; j < kN; ++j) {
    for (Eigen::Index i = 0; i < 3; ++i) x(i, j) = data_rng.normal();
    y(0, j) = 2 * x(0, j) - x(1, j) + 0.5 * x(2, j) + 1 + 0.1 * data_rng.normal();
  }
  MlpOptions mo;
  mo.inputs = 3;
  mo.outputs = 1;
  mo.hidden = {};
  mo.output_activation = Activation::linear;
  const Mlp mlp(mo);
  Rng init(4), dropout(5), shuffle(6);
  Eigen::VectorXd p;
  mlp.initialise(p, init);
  MlpRegressionObjective objective(mlp, x, y, dropout);
  SgdmOptions o;
  o.learning_rate = 0.1;
  o.momentum = 0.5;
  o.batch_size = kN;
  o.epochs = 3000;
  train_sgdm(objective, p, o, shuffle);
  Eigen::MatrixXd design(kN, 4);
  design << x.transpose(), Eigen::VectorXd::Ones(kN);
  const Eigen::VectorXd beta = design.colPivHouseholderQr().solve(y.transpose());
  EXPECT_LT((p - beta).norm(), 1e-9) << p.transpose() << "\n" << beta.transpose();
}

TEST(Sgdm, MomentumZeroIsPlainGradientDescent) {
  Quadratic q = scalar_quadratic(2, 3);
  Eigen::VectorXd w = Eigen::VectorXd::Constant(1, 0);
  SgdmOptions o;
  o.learning_rate = 0.1;
  o.momentum = 0.0;
  o.epochs = 1;
  Rng rng(1);
  train_sgdm(q, w, o, rng);
  EXPECT_DOUBLE_EQ(w[0], 0.0 - 0.1 * 2 * (0.0 - 3));
}

TEST(Sgdm, DivergenceIsATerminationNotAnException) {
  Quadratic q = scalar_quadratic(10, 1);
  Eigen::VectorXd w = Eigen::VectorXd::Constant(1, 0);
  SgdmOptions o;
  o.learning_rate = 10;  // |1 - eta a| = 99 > 1: diverges
  o.momentum = 0.0;
  o.epochs = 10000;
  Rng rng(1);
  const Summary s = train_sgdm(q, w, o, rng);
  EXPECT_EQ(s.termination, Termination::diverged);
  EXPECT_NE(s.message.find("diverged"), std::string::npos);
}

TEST(Sgdm, EarlyStopRestoresBestParameters) {
  Quadratic q = scalar_quadratic(1, 0);
  Eigen::VectorXd w = Eigen::VectorXd::Constant(1, 1);
  SgdmOptions o;
  o.learning_rate = 0.1;
  o.momentum = 0.0;
  o.epochs = 100;
  o.early_stop_patience = 3;
  // Validation loss is lowest when w is nearest 0.5 (reached after ~7 steps).
  SgdmHooks hooks;
  hooks.validation_loss = [](const Eigen::VectorXd& p) { return std::abs(p[0] - 0.5); };
  Rng rng(1);
  const Summary s = train_sgdm(q, w, o, rng, hooks);
  EXPECT_EQ(s.termination, Termination::early_stop);
  EXPECT_EQ(s.history.size(), s.best_epoch + 3);
  EXPECT_NEAR(w[0], std::pow(0.9, static_cast<double>(s.best_epoch)), 1e-15);
  EXPECT_LT(std::abs(w[0] - 0.5), 0.05);
}

TEST(Sgdm, CallbackCanStop) {
  Quadratic q = scalar_quadratic(1, 0);
  Eigen::VectorXd w = Eigen::VectorXd::Constant(1, 1);
  SgdmOptions o;
  o.epochs = 100;
  SgdmHooks hooks;
  hooks.on_epoch = [](const EpochRecord& e, const Eigen::VectorXd&) { return e.epoch < 4; };
  Rng rng(1);
  const Summary s = train_sgdm(q, w, o, rng, hooks);
  EXPECT_EQ(s.termination, Termination::stopped_by_callback);
  EXPECT_EQ(s.history.size(), 4u);
}

TEST(Sgdm, OptionsValidatedWithFieldAndValue) {
  SgdmOptions o;
  o.momentum = 1.5;
  try {
    o.validate();
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "momentum");
    EXPECT_NE(std::string(e.what()).find("[0, 1)"), std::string::npos);
  }
  o = {};
  o.learning_rate = -1;
  EXPECT_THROW(o.validate(), OptionError);
}

TEST(Sgdm, SameSeedsGiveBitIdenticalParameters) {
  Rng data_rng(3);
  Eigen::MatrixXd x = Eigen::MatrixXd::Random(4, 64), y = Eigen::MatrixXd::Random(1, 64);
  MlpOptions mo;
  mo.inputs = 4;
  mo.hidden = {8, 6};
  mo.dropout_keep_probability = 0.5;
  mo.weights = {Initializer::Kind::normal, 0.0, 0.3};
  const Mlp mlp(mo);
  const auto train = [&] {
    Rng init(1), dropout(2), shuffle(3);
    Eigen::VectorXd p;
    mlp.initialise(p, init);
    MlpRegressionObjective objective(mlp, x, y, dropout);
    SgdmOptions o;
    o.learning_rate = 0.01;
    o.batch_size = 5;
    o.epochs = 20;
    train_sgdm(objective, p, o, shuffle);
    return p;
  };
  const Eigen::VectorXd p1 = train(), p2 = train();
  EXPECT_EQ(p1, p2);
}

}  // namespace
}  // namespace cnclab
