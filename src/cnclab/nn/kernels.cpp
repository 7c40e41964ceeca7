#include "cnclab/nn/kernels.hpp"

#include <algorithm>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/nn/activation.hpp"

namespace cnclab::kernels {

static_assert(static_cast<int>(ActivationCode::relu) == static_cast<int>(Activation::relu) &&
              static_cast<int>(ActivationCode::tanh) == static_cast<int>(Activation::tanh) &&
              static_cast<int>(ActivationCode::sigmoid) == static_cast<int>(Activation::sigmoid) &&
              static_cast<int>(ActivationCode::linear) == static_cast<int>(Activation::linear));

const Table& table_for(IsaLevel level) {
  const auto compiled = compiled_isa_levels();
  if (std::find(compiled.begin(), compiled.end(), level) == compiled.end()) {
    throw ConfigError(std::string("this build has no ") + to_string(level) + " kernels");
  }
  if (!cpu_supports(level)) {
    throw ConfigError("this CPU does not support " + describe(level));
  }
  switch (level) {
#if CNCLAB_KERNEL_LEVELS == 3
    case IsaLevel::v3:
      return v3::table();
    case IsaLevel::v4:
      return v4::table();
#endif
    default:  // baseline, or native: the one compiled with the build's own flags
      return baseline::table();
  }
}

const Table& active() {
  static const Table& table = table_for(active_isa());
  return table;
}

}  // namespace cnclab::kernels
