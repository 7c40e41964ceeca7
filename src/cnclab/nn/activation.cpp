#include "cnclab/nn/activation.hpp"

#include "cnclab/core/enum_names.hpp"
#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

constexpr EnumName<Activation> kActivationNames[] = {{Activation::relu, "relu"},
                                                     {Activation::tanh, "tanh"},
                                                     {Activation::sigmoid, "sigmoid"},
                                                     {Activation::linear, "linear"}};

}  // namespace

Activation parse_activation(const std::string& name) {
  if (const auto a = enum_value(kActivationNames, name)) return *a;
  throw OptionError("activation", name, "must be one of: " + enum_name_list(kActivationNames));
}

std::string to_string(Activation a) {
  return enum_name(kActivationNames, a);
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
