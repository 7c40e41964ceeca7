#pragma once
#include <Eigen/Core>
#include <string>

namespace cnclab {

// relu(z) = max(0, z) (seed 000 Eq. 3); tanh; sigmoid(z) = 1/(1+e^-z); linear(z) = z.
enum class Activation { relu, tanh, sigmoid, linear };

// Throws OptionError("activation", name, "must be one of: ...").
Activation parse_activation(const std::string& name);
std::string to_string(Activation a);

// z <- f(z), elementwise (at this process's instruction-set level,
// nn/kernels.hpp).
void apply_activation(Activation f, Eigen::Ref<Eigen::MatrixXd> z);
void apply_activation(Activation f, Eigen::Ref<Eigen::MatrixXf> z);
// delta *= f'(z), written with the activation value a = f(z).
void multiply_derivative(Activation f, const Eigen::Ref<const Eigen::MatrixXd>& a,
                         Eigen::Ref<Eigen::MatrixXd> delta);
void multiply_derivative(Activation f, const Eigen::Ref<const Eigen::MatrixXf>& a,
                         Eigen::Ref<Eigen::MatrixXf> delta);

}  // namespace cnclab
