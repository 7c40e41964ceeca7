#include "cnclab/nn/activation.hpp"

#include "cnclab/core/error.hpp"

namespace cnclab {

Activation parse_activation(const std::string& name) {
  if (name == "relu") return Activation::relu;
  if (name == "tanh") return Activation::tanh;
  if (name == "sigmoid") return Activation::sigmoid;
  if (name == "linear") return Activation::linear;
  throw OptionError("activation", name, "must be one of: relu, tanh, sigmoid, linear");
}

std::string to_string(Activation a) {
  switch (a) {
    case Activation::relu:
      return "relu";
    case Activation::tanh:
      return "tanh";
    case Activation::sigmoid:
      return "sigmoid";
    case Activation::linear:
      return "linear";
  }
  return "?";
}

void apply_activation(Activation f, Eigen::Ref<Eigen::MatrixXd> z) {
  switch (f) {
    case Activation::relu:
      z = z.cwiseMax(0.0);
      break;
    case Activation::tanh:
      z = z.array().tanh();
      break;
    case Activation::sigmoid:
      z = (1.0 + (-z.array()).exp()).inverse();
      break;
    case Activation::linear:
      break;
  }
}

// delta *= f'(z), written with the activation value a = f(z).
void multiply_derivative(Activation f, const Eigen::Ref<const Eigen::MatrixXd>& a,
                         Eigen::Ref<Eigen::MatrixXd> delta) {
  switch (f) {
    case Activation::relu:
      delta = (a.array() > 0.0).select(delta, 0.0);
      break;
    case Activation::tanh:
      delta.array() *= 1.0 - a.array().square();
      break;
    case Activation::sigmoid:
      delta.array() *= a.array() * (1.0 - a.array());
      break;
    case Activation::linear:
      break;
  }
}

}  // namespace cnclab
