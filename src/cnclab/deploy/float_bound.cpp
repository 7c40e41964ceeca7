#include "cnclab/deploy/float_bound.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "cnclab/nn/minmax.hpp"

namespace cnclab {
namespace {

// A computed value and the bound on its error.
struct Ev {
  double v = 0.0, e = 0.0;
};

// The rules of float_bound.hpp.
class FloatArithmetic {
 public:
  explicit FloatArithmetic(const FloatBoundOptions& o) : u_(o.unit_roundoff), m_(o.math_ulps) {}

  // A constant stored as float: exact when float holds it.
  Ev constant(double c) const {
    return {c, static_cast<double>(static_cast<float>(c)) == c ? 0.0 : u_ * std::abs(c)};
  }
  Ev input(double x) const { return {x, u_ * std::abs(x)}; }
  Ev add(Ev a, Ev b) const { return rounded(a.v + b.v, a.e + b.e); }
  Ev sub(Ev a, Ev b) const { return rounded(a.v - b.v, a.e + b.e); }
  Ev mul(Ev a, Ev b) const {
    return rounded(a.v * b.v, std::abs(a.v) * b.e + std::abs(b.v) * a.e + a.e * b.e);
  }
  Ev div(Ev a, Ev b) const {
    const double q = a.v / b.v;
    if (!(std::abs(b.v) > b.e)) return {q, std::numeric_limits<double>::infinity()};
    return rounded(q, (a.e + std::abs(q) * b.e) / (std::abs(b.v) - b.e));
  }
  Ev tanh(Ev z) const {
    // max |tanh'| = 1 - tanh(m)^2 at the point of [z - E, z + E] nearest 0.
    const double nearest = std::max(0.0, std::abs(z.v) - z.e), t = std::tanh(nearest);
    return math(std::tanh(z.v), z.e * (1.0 - t * t));
  }
  Ev exp(Ev z) const {
    const double v = std::exp(z.v);
    return math(v, v * std::expm1(z.e));
  }
  Ev activation(Activation f, Ev z) const {
    switch (f) {
      case Activation::relu:
        return {std::max(z.v, 0.0), z.e};
      case Activation::tanh:
        return tanh(z);
      case Activation::sigmoid:  // 1 / (1 + exp(-z)), as the export computes it
        return div(constant(1), add(constant(1), exp({-z.v, z.e})));
      case Activation::linear:
        break;
    }
    return z;
  }

 private:
  // An exact result v of operands with errors adding up to `propagated`,
  // then rounded to float.
  Ev rounded(double v, double propagated) const {
    return {v, propagated + u_ * (std::abs(v) + propagated)};
  }
  // A math function's value v whose argument error moves it by `propagated`,
  // computed within m ulps (an ulp <= 2u |value|).
  Ev math(double v, double propagated) const {
    return {v, propagated + m_ * 2.0 * u_ * (std::abs(v) + propagated)};
  }

  double u_, m_;
};

// The normalisation of nn/scaling.hpp as the export computes it.
Ev scale_forward(const FloatArithmetic& f, const ScalingRecord& s, Eigen::Index i, Ev x) {
  if (s.method == Scaling::zscore) {
    return f.div(f.sub(x, f.constant(s.mean[i])), f.constant(s.std[i]));
  }
  if (s.method == Scaling::minmax) {
    const MinMaxNormaliser n(s.min, s.max, s.y_min, s.y_max);
    return f.add(f.mul(f.sub(x, f.constant(n.offset()[i])), f.constant(n.gain()[i])),
                 f.constant(s.y_min));
  }
  return x;
}

Ev scale_inverse(const FloatArithmetic& f, const ScalingRecord& s, Eigen::Index i, Ev y) {
  if (s.method == Scaling::zscore) {
    return f.add(f.mul(y, f.constant(s.std[i])), f.constant(s.mean[i]));
  }
  if (s.method == Scaling::minmax) {
    const MinMaxNormaliser n(s.min, s.max, s.y_min, s.y_max);
    return f.add(f.div(f.sub(y, f.constant(s.y_min)), f.constant(n.gain()[i])),
                 f.constant(n.offset()[i]));
  }
  return y;
}

Eigen::MatrixXd mlp_bound(const DeployedModel& m, const Eigen::MatrixXd& x,
                          const FloatArithmetic& f) {
  const Mlp mlp(m.mlp);
  const auto& sizes = mlp.layer_sizes();
  Eigen::MatrixXd bound(static_cast<Eigen::Index>(m.num_outputs()), x.cols());
  for (Eigen::Index s = 0; s < x.cols(); ++s) {
    std::vector<Ev> a(static_cast<std::size_t>(sizes[0]));
    for (Eigen::Index i = 0; i < sizes[0]; ++i) {
      a[static_cast<std::size_t>(i)] = scale_forward(f, m.input_scaling, i, f.input(x(i, s)));
    }
    Eigen::Index offset = 0;
    for (std::size_t l = 1; l < sizes.size(); ++l) {
      const Eigen::Index in = sizes[l - 1], out = sizes[l];
      const Activation act =
          l + 1 == sizes.size() ? m.mlp.output_activation : m.mlp.hidden_activation;
      std::vector<Ev> next(static_cast<std::size_t>(out));
      for (Eigen::Index i = 0; i < out; ++i) {
        Ev z{0.0, 0.0};
        for (Eigen::Index j = 0; j < in; ++j) {
          z = f.add(z, f.mul(f.constant(m.parameters[offset + j * out + i]),
                             a[static_cast<std::size_t>(j)]));
        }
        z = f.add(z, f.constant(m.parameters[offset + in * out + i]));
        next[static_cast<std::size_t>(i)] = f.activation(act, z);
      }
      a = std::move(next);
      offset += (in + 1) * out;
    }
    for (Eigen::Index k = 0; k < bound.rows(); ++k) {
      bound(k, s) = scale_inverse(f, m.target_scaling, k, a[static_cast<std::size_t>(k)]).e;
    }
  }
  return bound;
}

// scale_in, scale_out and unscale_out of the narx export.
Ev narx_in(const FloatArithmetic& f, const DeployedModel& m, std::size_t a, Ev x) {
  if (!m.has_physical_columns()) return x;
  const ColumnScaling& c = m.physical_inputs[a];
  return f.sub(f.mul(f.div(f.sub(x, f.constant(c.min)), f.constant(c.max - c.min)), f.constant(2)),
               f.constant(1));
}
Ev narx_out(const FloatArithmetic& f, const DeployedModel& m, std::size_t a, Ev y) {
  if (!m.has_physical_columns()) return y;
  const ColumnScaling& c = m.physical_targets[a];
  return f.add(f.constant(c.min),
               f.mul(f.mul(f.add(y, f.constant(1)), f.constant(0.5)), f.constant(c.max - c.min)));
}
Ev narx_unscale(const FloatArithmetic& f, const DeployedModel& m, std::size_t a, Ev x) {
  if (!m.has_physical_columns()) return x;
  const ColumnScaling& c = m.physical_targets[a];
  return f.sub(f.mul(f.div(f.sub(x, f.constant(c.min)), f.constant(c.max - c.min)), f.constant(2)),
               f.constant(1));
}

Eigen::MatrixXd narx_bound(const DeployedModel& m, const Eigen::MatrixXd& x,
                           const FloatArithmetic& f) {
  const NarxOptions& o = m.narx;
  const std::size_t h = o.hidden, dv = o.input_delays, de = o.feedback_delays,
                    d0 = o.first_input_delay;
  const auto hh = static_cast<Eigen::Index>(h), n = static_cast<Eigen::Index>(dv + de);
  Eigen::MatrixXd bound(static_cast<Eigen::Index>(m.networks.size()), x.cols());
  for (std::size_t a = 0; a < m.networks.size(); ++a) {
    const Eigen::VectorXd& q = m.networks[a].parameters;
    std::vector<Ev> v(d0 + dv, narx_in(f, m, a, f.constant(0))),
        e(de, narx_unscale(f, m, a, f.constant(0)));
    std::vector<Ev> r(static_cast<std::size_t>(n));
    for (Eigen::Index t = 0; t < x.cols(); ++t) {
      for (std::size_t k = v.size() - 1; k > 0; --k) v[k] = v[k - 1];
      v[0] = narx_in(f, m, a, f.input(x(static_cast<Eigen::Index>(a), t)));
      for (std::size_t j = 0; j < dv; ++j) r[j] = v[d0 + j];
      for (std::size_t k = 0; k < de; ++k) r[dv + k] = e[k];
      Ev y{0.0, 0.0};
      for (Eigen::Index i = 0; i < hh; ++i) {
        Ev z{0.0, 0.0};
        for (Eigen::Index j = 0; j < n; ++j) {
          z = f.add(z, f.mul(f.constant(q[j * hh + i]), r[static_cast<std::size_t>(j)]));
        }
        z = f.add(z, f.constant(q[hh * n + i]));
        y = f.add(y, f.mul(f.constant(q[hh * n + hh + i]), f.activation(o.hidden_activation, z)));
      }
      y = f.add(y, f.constant(q[hh * n + 2 * hh]));
      for (std::size_t k = de - 1; k > 0; --k) e[k] = e[k - 1];
      e[0] = y;
      bound(static_cast<Eigen::Index>(a), t) = narx_out(f, m, a, y).e;
    }
  }
  return bound;
}

}  // namespace

Eigen::MatrixXd float_error_bound(const DeployedModel& m, const Eigen::MatrixXd& x,
                                  const FloatBoundOptions& options) {
  const FloatArithmetic f(options);
  return m.kind == ModelKind::mlp ? mlp_bound(m, x, f) : narx_bound(m, x, f);
}

}  // namespace cnclab
