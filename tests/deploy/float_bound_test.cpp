// The float bound (float_bound.hpp) against float arithmetic done here,
// independently of the exports: a plain float evaluation of random networks
// never leaves the bound around the double prediction (nn/mlp.hpp,
// nn/narx.hpp through predict()), and the bound is small enough to use.
#include "cnclab/deploy/float_bound.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "cnclab/core/rng.hpp"
#include "cnclab/deploy/predict.hpp"
#include "common/stable_narx.hpp"

namespace cnclab {
namespace {

float activation(Activation f, float z) {
  switch (f) {
    case Activation::relu:
      return z > 0.0f ? z : 0.0f;
    case Activation::tanh:
      return std::tanh(z);
    case Activation::sigmoid:
      return 1.0f / (1.0f + std::exp(-z));
    case Activation::linear:
      break;
  }
  return z;
}

DeployedModel random_mlp(Activation hidden, Activation output, Scaling scaling,
                         std::uint64_t seed) {
  DeployedModel m;
  m.kind = ModelKind::mlp;
  m.mlp.inputs = 6;
  m.mlp.hidden = {12, 7};
  m.mlp.outputs = 2;
  m.mlp.hidden_activation = hidden;
  m.mlp.output_activation = output;
  m.mlp.weights = {Initializer::Kind::xavier};
  const Mlp mlp(m.mlp);
  Rng rng(seed);
  mlp.initialise(m.parameters, rng);
  Eigen::MatrixXd x_train(6, 50), y_train(2, 50);
  for (Eigen::Index i = 0; i < x_train.size(); ++i) x_train(i) = 100.0 * (rng.uniform() - 0.3);
  for (Eigen::Index i = 0; i < y_train.size(); ++i) y_train(i) = 5.0 * rng.uniform() + 1.0;
  m.input_scaling = ScalingRecord::fit(scaling, x_train);
  m.target_scaling = ScalingRecord::fit(scaling, y_train, {0.1, 0.9});
  m.input_names = {"a", "b", "c", "d", "e", "f"};
  m.input_units.assign(6, "mm");
  m.target_names = {"y", "z"};
  m.target_units = {"µm", "µm"};
  return m;
}

// The mlp in float, as a C compiler evaluates the export's loops.
Eigen::VectorXd float_mlp(const DeployedModel& m, const Eigen::VectorXd& x_double) {
  const Mlp mlp(m.mlp);
  const auto& sizes = mlp.layer_sizes();
  const Eigen::VectorXf x = x_double.cast<float>();
  Eigen::VectorXf a(sizes[0]);
  const ScalingRecord& in = m.input_scaling;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    if (in.method == Scaling::zscore) {
      a[i] = (x[i] - static_cast<float>(in.mean[i])) / static_cast<float>(in.std[i]);
    } else {
      const MinMaxNormaliser n(in.min, in.max, in.y_min, in.y_max);
      a[i] = (x[i] - static_cast<float>(n.offset()[i])) * static_cast<float>(n.gain()[i]) +
             static_cast<float>(in.y_min);
    }
  }
  Eigen::Index offset = 0;
  for (std::size_t l = 1; l < sizes.size(); ++l) {
    const Eigen::Index n_in = sizes[l - 1], n_out = sizes[l];
    Eigen::VectorXf next(n_out);
    for (Eigen::Index i = 0; i < n_out; ++i) {
      float z = 0.0f;
      for (Eigen::Index j = 0; j < n_in; ++j) {
        z += static_cast<float>(m.parameters[offset + j * n_out + i]) * a[j];
      }
      z += static_cast<float>(m.parameters[offset + n_in * n_out + i]);
      next[i] =
          activation(l + 1 == sizes.size() ? m.mlp.output_activation : m.mlp.hidden_activation, z);
    }
    a = next;
    offset += (n_in + 1) * n_out;
  }
  Eigen::VectorXd y(a.size());
  const ScalingRecord& out = m.target_scaling;
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    if (out.method == Scaling::zscore) {
      y[k] = a[k] * static_cast<float>(out.std[k]) + static_cast<float>(out.mean[k]);
    } else {
      const MinMaxNormaliser n(out.min, out.max, out.y_min, out.y_max);
      y[k] = (a[k] - static_cast<float>(out.y_min)) / static_cast<float>(n.gain()[k]) +
             static_cast<float>(n.offset()[k]);
    }
  }
  return y;
}

TEST(FloatBound, HoldsForFloatMlpsAndIsSmall) {
  struct Case {
    Activation hidden, output;
    Scaling scaling;
  };
  for (const Case c : {Case{Activation::relu, Activation::linear, Scaling::zscore},
                       Case{Activation::sigmoid, Activation::sigmoid, Scaling::minmax},
                       Case{Activation::tanh, Activation::linear, Scaling::minmax}}) {
    const DeployedModel m = random_mlp(c.hidden, c.output, c.scaling, 3);
    Rng rng(5);
    Eigen::MatrixXd x(6, 400);
    for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = 120.0 * (rng.uniform() - 0.35);
    const Eigen::MatrixXd reference = m.target_scaling.inverse_transform(
        Mlp(m.mlp).predict(m.parameters, m.input_scaling.transform(x)));
    const Eigen::MatrixXd bound = float_error_bound(m, x);
    double worst_ratio = 0;
    for (Eigen::Index s = 0; s < x.cols(); ++s) {
      const Eigen::VectorXd y = float_mlp(m, x.col(s));
      for (Eigen::Index k = 0; k < 2; ++k) {
        const double diff = std::abs(y[k] - reference(k, s));
        EXPECT_LE(diff, bound(k, s)) << "sample " << s << " output " << k;
        worst_ratio = std::max(worst_ratio, bound(k, s) / std::max(1.0, std::abs(reference(k, s))));
      }
    }
    EXPECT_LT(worst_ratio, 1e-4) << "a bound this loose says nothing";
  }
}

TEST(FloatBound, HoldsAlongAFloatNarxClosedLoop) {
  NarxOptions o;  // seed 002: 12 tanh units, 4 input and 4 feedback delays
  DeployedModel m;
  m.kind = ModelKind::narx;
  m.narx = o;
  for (const char* axis : {"x", "y"}) {
    const NarxAxisModel a = testing::stable_narx_model(o, axis[0] == 'x' ? 1 : 2);
    m.networks.push_back({axis, std::string("v_") + axis, std::string("e_") + axis, a.params});
    m.input_names.push_back(std::string("v_") + axis);
    m.target_names.push_back(std::string("e_") + axis);
    m.physical_inputs.push_back({std::string("v_ref_") + axis, "mm/s", -300.0, 300.0});
    m.physical_targets.push_back({std::string("e_ref_") + axis, "µm", -200.0, 250.0});
  }
  m.input_units = m.target_units = {"1", "1"};
  const Eigen::Index ticks = 3000;
  PredictionInput in;
  in.source = "test";
  in.samples = static_cast<std::size_t>(ticks);
  Eigen::MatrixXd x(2, ticks);
  for (Eigen::Index a = 0; a < 2; ++a) {
    for (Eigen::Index t = 0; t < ticks; ++t) x(a, t) = testing::test_velocity(t, 0.7 * a);
    in.columns.push_back(
        {m.physical_inputs[static_cast<std::size_t>(a)].name, "mm/s", x.row(a).transpose()});
  }
  const Prediction reference = predict(m, in);
  const Eigen::MatrixXd bound = float_error_bound(m, x);
  for (std::size_t a = 0; a < 2; ++a) {
    const Eigen::VectorXd& q = m.networks[a].parameters;
    const ColumnScaling &ci = m.physical_inputs[a], &co = m.physical_targets[a];
    const auto scale = [](float v, const ColumnScaling& c) {
      return (v - static_cast<float>(c.min)) / static_cast<float>(c.max - c.min) * 2.0f - 1.0f;
    };
    std::vector<float> v(4, scale(0.0f, ci)), e(4, scale(0.0f, co));
    const NamedColumn* ref = nullptr;
    for (const auto& c : reference.columns) {
      if (c.name == co.name + ".closed_loop") ref = &c;
    }
    ASSERT_NE(ref, nullptr);
    double worst = 0;
    for (Eigen::Index t = 0; t < ticks; ++t) {
      for (std::size_t k = 3; k > 0; --k) v[k] = v[k - 1];
      v[0] = scale(static_cast<float>(x(static_cast<Eigen::Index>(a), t)), ci);
      float r[8], y = 0.0f;
      for (int j = 0; j < 4; ++j)
        r[j] = v[static_cast<std::size_t>(j)], r[4 + j] = e[static_cast<std::size_t>(j)];
      for (Eigen::Index i = 0; i < 12; ++i) {
        float z = 0.0f;
        for (Eigen::Index j = 0; j < 8; ++j) z += static_cast<float>(q[j * 12 + i]) * r[j];
        z += static_cast<float>(q[96 + i]);
        y += static_cast<float>(q[108 + i]) * std::tanh(z);
      }
      y += static_cast<float>(q[120]);
      for (std::size_t k = 3; k > 0; --k) e[k] = e[k - 1];
      e[0] = y;
      const float out =
          static_cast<float>(co.min) + (y + 1.0f) * 0.5f * static_cast<float>(co.max - co.min);
      const double diff = std::abs(static_cast<double>(out) - ref->values[t]);
      EXPECT_LE(diff, bound(static_cast<Eigen::Index>(a), t)) << "network " << a << " tick " << t;
      worst = std::max(worst, bound(static_cast<Eigen::Index>(a), t));
    }
    EXPECT_LT(worst, 0.1) << "µm: the loop must not blow the bound up";
  }
}

}  // namespace
}  // namespace cnclab
