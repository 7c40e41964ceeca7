// Adam (train/adam.hpp) against torch.optim.Adam in float64: the numbers
// below are the output of
//   /usr/bin/python3 tests/train/adam_reference.py
// which trains the same 5-6-4-1 ReLU network with dropout after both hidden
// layers on Friedman #1 data, from the same weights, with the same dropout
// masks and batches (closed forms, listed in the script). Agreement is to
// 1e-12 of the largest parameter (max |w - w_torch| <= 1e-12 max |w_torch|):
// the two sides sum the products in different orders and PyTorch fuses some
// multiply-adds, so the last bits differ.
#include "cnclab/train/adam.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

constexpr std::size_t kSamples = 60;
constexpr double kKeep = 0.8;

struct TorchRun {
  std::string name;
  double last_epoch_loss;          // mean mini-batch loss of the last epoch
  std::vector<double> parameters;  // after training, cnclab's flat layout
};

const std::vector<TorchRun> kTorch = {
    // adam_reference.py's output (PyTorch 1.13.0a0).
    // one_epoch
    {"one_epoch",
     2.8403114338131021,
     {0.38139372647301623,   0.4189746734839756,    0.11043905651326225,  -0.41621674861508989,
      -0.47946213733156923,  -0.13970774909946293,  0.28907308497034206,  0.45624793009182973,
      0.24597147138408512,   -0.31070503599280913,  -0.49999510327535174, -0.26828645900021747,
      0.17134437628162025,   0.45605756016990118,   0.36487755742305944,  -0.18216900891599444,
      -0.4806987459397784,   -0.37549362338583803,  0.035515421490860316, 0.41822611253769143,
      0.45840898812496594,   -0.043067987627548245, -0.42311020208758532, -0.45278918100331195,
      -0.10604281399676491,  0.34391500920431317,   0.51813074676457105,  0.097119879766204509,
      -0.33181694210648377,  -0.49401581204643091,  -0.24150805897170038, 0.23743117585789306,
      0.53995520346260883,   0.22601537108311232,   -0.21409133474807551, -0.49588942672155789,
      -0.28242586439240441,  0.12751714341707746,   0.44348385608523455,  0.33607977157480273,
      -0.039318982994935178, -0.45826077395781689,  -0.41588737131429915, -0.028867357110973543,
      0.4652601515205243,    0.43363662660086477,   0.021984987525800619, -0.41547284851318245,
      -0.44074392790316652,  -0.13552976864132549,  0.31254468701315996,  0.48750253692044687,
      0.19796257509091708,   -0.27939452442580814,  -0.49987758667930993, -0.26077550104345593,
      0.21808237762391247,   0.49643632404226856,   0.31836900356956893,  -0.15240531055110834,
      -0.44327582237285784,  -0.38768884021247446,  0.044087724827155672, 0.42192396054204889,
      0.45081176412722379,   0.026478886427621057,  -0.38896298712857941, -0.40945212709151035,
      -0.017602030535333969}},
    // fifty_epochs
    {"fifty_epochs",
     0.093507711085158943,
     {0.23131627416731423,  1.2913441011420099,   0.64610938258221251,   -0.48670060517119573,
      -0.47946213733156923, -0.13970774909946293, 0.14561524972549544,   0.68031529798970325,
      0.26433697883923296,  -0.38727367579716687, -0.49999510327535174,  -0.26828645900021747,
      0.025154964994916696, -0.64245332822700252, -0.26400389776124955,  -0.2554484039202054,
      -0.4806987459397784,  -0.37549362338583803, -0.11331909844767364,  1.0038544536481433,
      0.81662063660138795,  -0.11933084804280351, -0.42311020208758532,  -0.45278918100331195,
      -0.24159987940825395, -0.40961525872074817, -0.012272965997136787, 0.023024319734501902,
      -0.33181694210648377, -0.49401581204643091, -0.3866671440727284,   0.15133336237253667,
      0.4119551046240067,   0.15052347054227577,  -0.21409133474807551,  -0.49588942672155789,
      -0.13952641313802258, 0.24593794747771885,  0.3330459289648427,    0.24417926179976368,
      0.3954366569384074,   0.59241218988643707,  -0.41588737131429915,  -0.2681726016699596,
      0.47884831192911742,  0.58701500175118781,  -0.11818793163802566,  -0.46039635647469984,
      -0.38262624168864062, -0.12327362964096698, 0.25777321412987736,   0.44102655236160643,
      0.19796257509091708,  -0.27939452442580814, -0.49987758667930993,  -0.26077550104345593,
      0.21808237762391247,  0.49643632404226856,  0.31836900356956893,   -0.15240531055110834,
      -0.29294666935455421, 0.16802814542154548,  -0.091219726384280816, 0.13887068094102709,
      0.46798509684383788,  0.27773030515433628,  -0.28807514213681207,  -0.22321408392083808,
      0.71680292954760916}},
    // fifty_epochs_decay_amsgrad
    {"fifty_epochs_decay_amsgrad",
     0.21125103785273491,
     {0.27890814037791639,    0.96181965789646962,     0.44690987663113602,
      -0.41821023692629694,   -0.012845418043240636,   1.2388032987692939e-10,
      0.19753552667118715,    0.70698842364896863,     0.34879516317274328,
      -0.11163354314329021,   -0.016524614869825961,   -2.7967287079799069e-05,
      0.085322452743051849,   -0.0032576505810248029,  0.029694852252375777,
      0.19752672195592116,    -0.013051388706041549,   -0.0020689126784047712,
      -0.046846368082046473,  0.86325839931901349,     0.72212926284175838,
      -0.090827803330139914,  -0.0055013547013838607,  -0.0088825022714248848,
      -0.15976743709367366,   0.1414156205190569,      0.24963082510886231,
      0.3300770643569641,     -0.00059380852533143648, -0.015396127863619054,
      -0.31143884208568856,   0.61699938420275346,     0.59006746130983945,
      0.33849985605014288,    -2.8343397579886046e-09, -0.015744786021201648,
      -0.18293524482367329,   0.010223729810536654,    0.33213940601815406,
      0.27085542092757886,    0.20315659518270898,     0.45743939385048971,
      -0.0048317240737760078, -0.19662066429665406,    0.56317843119174382,
      0.54968167557136605,    -0.039190068205277255,   -0.38823989935506453,
      -0.70004111997443219,   -0.35020834633326758,    0.0095785242140555022,
      0.02228079738208175,    -1.7697132540141345e-09, -5.6902941412908374e-05,
      -0.016501991818039352,  -1.6158912011623872e-05, 4.4749306704160159e-08,
      0.015847409440515024,   0.00036479447571415442,  -1.8012438063488916e-10,
      -0.31484003431062563,   0.29915141543571644,     -0.014542981859314437,
      0.22532853925283045,    0.59830584818940868,     0.33822628669099603,
      -0.3238966810090953,    -0.2811799941919006,     0.36566534238382697}},
};

Mlp network() {
  MlpOptions o;
  o.inputs = 5;
  o.hidden = {6, 4};
  o.outputs = 1;
  o.hidden_activation = Activation::relu;
  o.dropout_keep_probability = kKeep;
  o.dropout_placement = DropoutPlacement::after_every_hidden;
  return Mlp(o);
}

// Friedman #1 (Friedman 1991, Eq. 1) without noise, scaled by 1/10, on a
// golden-ratio sequence of inputs (adam_reference.py).
void friedman1(Eigen::MatrixXd& x, Eigen::MatrixXd& y) {
  x.resize(5, kSamples);
  y.resize(1, kSamples);
  for (std::size_t s = 0; s < kSamples; ++s) {
    for (std::size_t j = 0; j < 5; ++j) {
      x(j, s) = std::fmod(static_cast<double>(5 * s + j + 1) * 0.6180339887498949, 1.0);
    }
    const double d = x(2, s) - 0.5;
    y(0, s) = (10.0 * std::sin(std::numbers::pi * x(0, s) * x(1, s)) + 20.0 * (d * d) +
               10.0 * x(3, s) + 5.0 * x(4, s)) /
              10.0;
  }
}

Eigen::VectorXd initial_parameters(std::size_t n) {
  Eigen::VectorXd w(static_cast<Eigen::Index>(n));
  for (Eigen::Index k = 0; k < w.size(); ++k) w(k) = 0.5 * std::sin(static_cast<double>(k + 1));
  return w;
}

// The network's MSE with the script's dropout masks: at update t, unit i of
// hidden layer l for sample s is kept (scaled by 1 / 0.8) unless
// (131 t + 31 l + 17 i + 7 s) mod 5 == 0.
class ClosedFormDropoutObjective : public SeparableObjective {
 public:
  ClosedFormDropoutObjective(const Mlp& mlp, const Eigen::MatrixXd& x, const Eigen::MatrixXd& y)
      : mlp_(mlp), x_(x), y_(y) {}
  std::size_t num_samples() const override { return kSamples; }
  std::size_t num_parameters() const override { return mlp_.num_parameters(); }
  double loss_and_gradient(const Eigen::VectorXd& params, std::span<const std::size_t> batch,
                           Eigen::VectorXd& gradient) override {
    ++t_;
    const auto b = static_cast<Eigen::Index>(batch.size());
    Eigen::MatrixXd xb(x_.rows(), b), yb(y_.rows(), b);
    for (Eigen::Index c = 0; c < b; ++c) {
      xb.col(c) = x_.col(static_cast<Eigen::Index>(batch[c]));
      yb.col(c) = y_.col(static_cast<Eigen::Index>(batch[c]));
    }
    mlp_.prepare(ws_, b);
    for (std::size_t l = 1; l + 1 < ws_.mask.size(); ++l) {
      for (Eigen::Index i = 0; i < ws_.mask[l].rows(); ++i) {
        for (Eigen::Index c = 0; c < b; ++c) {
          const std::size_t key =
              131 * t_ + 31 * l + 17 * static_cast<std::size_t>(i) + 7 * batch[c];
          ws_.mask[l](i, c) = key % 5 == 0 ? 0.0 : 1.0 / kKeep;
        }
      }
    }
    return mlp_.loss_and_gradient(params, xb, yb, ws_, gradient);
  }

 private:
  const Mlp& mlp_;
  const Eigen::MatrixXd& x_;
  const Eigen::MatrixXd& y_;
  Mlp::Workspace ws_;
  std::size_t t_ = 0;
};

struct Case {
  std::string name;
  AdamOptions options;
};

// adam_reference.py's CASES, in its order.
std::vector<Case> cases() {
  AdamOptions base;
  base.batch_size = 16;
  base.shuffle = false;
  base.learning_rate = 0.01;
  AdamOptions one = base, fifty = base, decay = base;
  one.epochs = 1;
  fifty.epochs = 50;
  decay.epochs = 50;
  decay.learning_rate = 0.005;
  decay.beta1 = 0.8;
  decay.beta2 = 0.99;
  decay.eps = 1e-6;
  decay.weight_decay = 0.01;
  decay.amsgrad = true;
  return {{"one_epoch", one}, {"fifty_epochs", fifty}, {"fifty_epochs_decay_amsgrad", decay}};
}

TEST(Adam, EqualsTorchOptimAdamInFloat64) {
  const Mlp mlp = network();
  Eigen::MatrixXd x, y;
  friedman1(x, y);
  const auto all = cases();
  ASSERT_EQ(all.size(), kTorch.size());
  for (std::size_t c = 0; c < all.size(); ++c) {
    SCOPED_TRACE(all[c].name);
    ASSERT_EQ(all[c].name, kTorch[c].name);
    ClosedFormDropoutObjective objective(mlp, x, y);
    Eigen::VectorXd w = initial_parameters(mlp.num_parameters());
    Rng unused(1, "shuffle");
    const Summary s = train_adam(objective, w, all[c].options, unused);
    EXPECT_EQ(s.termination, Termination::max_epochs);
    ASSERT_EQ(s.history.size(), all[c].options.epochs);
    const Eigen::Map<const Eigen::VectorXd> torch(
        kTorch[c].parameters.data(), static_cast<Eigen::Index>(kTorch[c].parameters.size()));
    ASSERT_EQ(w.size(), torch.size());
    EXPECT_LE((w - torch).cwiseAbs().maxCoeff(), 1e-12 * torch.cwiseAbs().maxCoeff());
    EXPECT_NEAR(s.history.back().train_loss, kTorch[c].last_epoch_loss,
                1e-12 * kTorch[c].last_epoch_loss);
  }
}

TEST(Adam, ZeroEpochsLeaveTheParametersBitIdentical) {
  const Mlp mlp = network();
  Eigen::MatrixXd x, y;
  friedman1(x, y);
  ClosedFormDropoutObjective objective(mlp, x, y);
  const Eigen::VectorXd w0 = initial_parameters(mlp.num_parameters());
  Eigen::VectorXd w = w0;
  AdamOptions o;
  o.epochs = 0;
  Rng rng(1, "shuffle");
  train_adam(objective, w, o, rng);
  EXPECT_EQ(w, w0);
}

TEST(Adam, OptionsValidatedWithFieldAndValue) {
  const auto message = [](AdamOptions o) {
    try {
      o.validate();
    } catch (const OptionError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  AdamOptions o;
  o.beta2 = 1.0;
  EXPECT_NE(message(o).find("beta2"), std::string::npos) << message(o);
  o = {};
  o.eps = 0;
  EXPECT_NE(message(o).find("eps"), std::string::npos) << message(o);
  o = {};
  o.weight_decay = -1e-3;
  EXPECT_NE(message(o).find("weight_decay"), std::string::npos) << message(o);
}

TEST(Adam, RegistryDeclaresItsCapabilities) {
  TrainerRegistry registry;
  registry.add(adam_trainer());
  const TrainerDef* adam = registry.find("adam");
  ASSERT_NE(adam, nullptr);
  EXPECT_TRUE(adam->capabilities.dropout);
  EXPECT_TRUE(adam->capabilities.mini_batches);
  EXPECT_TRUE(adam->capabilities.validation_stop);
  EXPECT_FALSE(adam->capabilities.needs_jacobian);
  EXPECT_NE(trainers().find("adam"), nullptr);  // registered among the built-ins
}

}  // namespace
}  // namespace cnclab
