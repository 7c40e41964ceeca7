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

}  // namespace cnclab
