#include "cnclab/core/isa.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cstdlib>

#include "cnclab/core/eigen_cache_sizes.hpp"
#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

// CNCLAB_KERNEL_LEVELS (CMake): 3 when the build compiles baseline, v3 and
// v4 kernels (x86-64, CNCLAB_NATIVE_ARCH=OFF), 1 when it compiles only the
// default flags' kernels.
#ifndef CNCLAB_KERNEL_LEVELS
#define CNCLAB_KERNEL_LEVELS 1
#endif

constexpr IsaLevel kLevels[] = {IsaLevel::baseline, IsaLevel::v3, IsaLevel::v4, IsaLevel::native};

// Set before main(): every product, from the first, sums in the fixed order.
[[maybe_unused]] const bool kEigenCachesPinned = [] {
  Eigen::setCpuCacheSizes(kEigenL1CacheBytes, kEigenL2CacheBytes, kEigenL3CacheBytes);
  return true;
}();

std::string known_names(const std::vector<IsaLevel>& levels) {
  std::string s;
  for (const IsaLevel l : levels) s += (s.empty() ? "" : ", ") + std::string(to_string(l));
  return s;
}

}  // namespace

const char* to_string(IsaLevel level) {
  switch (level) {
    case IsaLevel::baseline:
      return "baseline";
    case IsaLevel::v3:
      return "v3";
    case IsaLevel::v4:
      return "v4";
    case IsaLevel::native:
      return "native";
  }
  return "?";
}

std::string describe(IsaLevel level) {
  switch (level) {
    case IsaLevel::baseline:
#if defined(__x86_64__)
      return "baseline (x86-64: SSE2)";
#else
      return "baseline (this CPU family's default flags)";
#endif
    case IsaLevel::v3:
      return "v3 (x86-64-v3: AVX2 + FMA)";
    case IsaLevel::v4:
      return "v4 (x86-64-v4: AVX-512 F/CD/BW/DQ/VL + AVX2 + FMA)";
    case IsaLevel::native:
      return "native (-march=native: the build machine's CPU, CNCLAB_NATIVE_ARCH=ON)";
  }
  return "?";
}

std::vector<IsaLevel> compiled_isa_levels() {
#if defined(CNCLAB_NATIVE_ARCH)
  return {IsaLevel::native};
#elif CNCLAB_KERNEL_LEVELS == 3
  return {IsaLevel::baseline, IsaLevel::v3, IsaLevel::v4};
#else
  return {IsaLevel::baseline};
#endif
}

bool cpu_supports(IsaLevel level) {
  switch (level) {
    case IsaLevel::baseline:
    case IsaLevel::native:  // the binary itself needs it: it runs, so yes
      return true;
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    // __builtin_cpu_supports checks the CPU's feature bits and, for AVX and
    // AVX-512, that the operating system saves the vector registers (XCR0).
    case IsaLevel::v3:
      return __builtin_cpu_supports("avx") && __builtin_cpu_supports("avx2") &&
             __builtin_cpu_supports("fma");
    case IsaLevel::v4:
      return cpu_supports(IsaLevel::v3) && __builtin_cpu_supports("avx512f") &&
             __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
#else
    default:
      return false;
#endif
  }
  return false;
}

IsaLevel choose_isa(std::string_view requested, const std::vector<IsaLevel>& compiled,
                    const std::function<bool(IsaLevel)>& supported) {
  if (requested.empty()) {
    for (auto it = compiled.rbegin(); it != compiled.rend(); ++it) {
      if (supported(*it)) return *it;
    }
    throw ConfigError(
        "no compiled kernel level runs on this CPU (compiled: " + known_names(compiled) + ")");
  }
  const auto* named = std::find_if(std::begin(kLevels), std::end(kLevels),
                                   [&](IsaLevel l) { return requested == to_string(l); });
  const std::string where = "CNCLAB_ISA=" + std::string(requested);
  if (named == std::end(kLevels)) {
    throw ConfigError(where + ": unknown level; this build has: " + known_names(compiled));
  }
  if (std::find(compiled.begin(), compiled.end(), *named) == compiled.end()) {
    throw ConfigError(where +
                      ": this build has no kernels for it (it has: " + known_names(compiled) + ")");
  }
  if (!supported(*named)) {
    throw ConfigError(where + ": this CPU does not support " + describe(*named) +
                      "; unset CNCLAB_ISA to use the widest level it supports");
  }
  return *named;
}

IsaLevel active_isa() {
  static const IsaLevel level = [] {
    const char* env = std::getenv("CNCLAB_ISA");
    return choose_isa(env ? env : "", compiled_isa_levels(), cpu_supports);
  }();
  return level;
}

}  // namespace cnclab
