#include "cnclab/nn/activation.hpp"

#include "cnclab/core/enum_names.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/nn/kernels.hpp"

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
  kernels::active().dactivate(static_cast<kernels::ActivationCode>(f), z.rows(), z.cols(), z.data(),
                              z.outerStride());
}

void apply_activation(Activation f, Eigen::Ref<Eigen::MatrixXf> z) {
  kernels::active().sactivate(static_cast<kernels::ActivationCode>(f), z.rows(), z.cols(), z.data(),
                              z.outerStride());
}

void multiply_derivative(Activation f, const Eigen::Ref<const Eigen::MatrixXd>& a,
                         Eigen::Ref<Eigen::MatrixXd> delta) {
  kernels::active().dderivative(static_cast<kernels::ActivationCode>(f), a.rows(), a.cols(),
                                a.data(), a.outerStride(), delta.data(), delta.outerStride());
}

void multiply_derivative(Activation f, const Eigen::Ref<const Eigen::MatrixXf>& a,
                         Eigen::Ref<Eigen::MatrixXf> delta) {
  kernels::active().sderivative(static_cast<kernels::ActivationCode>(f), a.rows(), a.cols(),
                                a.data(), a.outerStride(), delta.data(), delta.outerStride());
}

}  // namespace cnclab
