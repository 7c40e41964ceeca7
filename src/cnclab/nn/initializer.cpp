#include "cnclab/nn/initializer.hpp"

#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/nn/mlp_fields.hpp"

namespace cnclab {

void Initializer::validate() const {
  initializer_fields().check(*this);  // the declared rules of the fields `kind` uses
  if (kind == Kind::uniform && !(low < high)) {
    throw OptionError("high", std::to_string(high),
                      "must be finite and greater than low = " + std::to_string(low));
  }
}

void Initializer::fill(Eigen::Ref<Eigen::MatrixXd> out, Eigen::Index fan_in, Eigen::Index fan_out,
                       Rng& rng) const {
  const auto draw = [&]() -> double {
    switch (kind) {
      case Kind::normal:
        return rng.normal(mean, std);
      case Kind::uniform:
        return rng.uniform(low, high);
      case Kind::xavier: {
        const double a = std::sqrt(6.0 / static_cast<double>(fan_in + fan_out));
        return rng.uniform(-a, a);
      }
      case Kind::he:
        return rng.normal(0.0, std::sqrt(2.0 / static_cast<double>(fan_in)));
    }
    return 0.0;
  };
  for (Eigen::Index j = 0; j < out.cols(); ++j) {
    for (Eigen::Index i = 0; i < out.rows(); ++i) out(i, j) = draw();
  }
}

std::string to_string(Initializer::Kind kind) {
  switch (kind) {
    case Initializer::Kind::normal:
      return "normal";
    case Initializer::Kind::uniform:
      return "uniform";
    case Initializer::Kind::xavier:
      return "xavier";
    case Initializer::Kind::he:
      return "he";
  }
  return "?";
}

}  // namespace cnclab
