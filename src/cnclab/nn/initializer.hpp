#pragma once
// Weight and bias initialisers.
#include <Eigen/Core>
#include <string>

#include "cnclab/core/rng.hpp"

namespace cnclab {

struct Initializer {
  enum class Kind {
    normal,   // N(mean, std^2)       seed 000 Eq. 10: weights N(0, 1)
    uniform,  // U(low, high)          seed 000 Eq. 11: biases U(c, d)
    xavier,   // U(+-sqrt(6 / (fan_in + fan_out)))   Glorot & Bengio 2010
    he,       // N(0, 2 / fan_in)                     He et al. 2015
  };
  Kind kind = Kind::normal;
  double mean = 0.0;
  double std = 1.0;
  double low = 0.0;
  double high = 0.1;
  // std >= 0 and finite; low < high; all finite.
  void validate() const;
  // Fills `out` (fan_out x fan_in for weights, fan_out x 1 for biases).
  void fill(Eigen::Ref<Eigen::MatrixXd> out, Eigen::Index fan_in, Eigen::Index fan_out,
            Rng& rng) const;
};

std::string to_string(Initializer::Kind kind);

}  // namespace cnclab
