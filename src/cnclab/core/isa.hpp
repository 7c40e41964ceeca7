#pragma once
// Instruction-set levels of the hot numerical kernels (nn/kernels.hpp: the
// J^T J / J^T e build, the MLP products, the NARX RTRL recursion) and the one
// this process runs them at.
//
// A default x86-64 build compiles those kernels three times, each with fixed
// compiler flags (never -march=native), and picks one when the process starts:
//   baseline  x86-64 (SSE2): every x86-64 CPU
//   v3        + AVX2 and FMA (-mavx2 -mfma; the vector part of x86-64-v3)
//   v4        + AVX-512 F, CD, BW, DQ, VL (the vector part of x86-64-v4)
// The widest level the CPU supports is chosen; the environment variable
// CNCLAB_ISA=baseline|v3|v4 forces one (an unknown name, or a level this CPU
// or this build lacks, is a ConfigError naming CNCLAB_ISA). Within a level a
// result is the same bit for bit on every machine that runs it (same binary);
// between levels it agrees to rounding (FMA and vector width change the order
// of the sums). Provenance records the level (io/provenance.hpp).
// A build with -DCNCLAB_NATIVE_ARCH=ON compiles everything for the build
// machine's CPU and has one level, "native". Other CPU families: "baseline".
// Details and measured speeds: docs/performance.md.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace cnclab {

enum class IsaLevel { baseline, v3, v4, native };

// The name CNCLAB_ISA takes: "baseline", "v3", "v4", "native".
const char* to_string(IsaLevel level);
// For people: "v4 (AVX-512 F/CD/BW/DQ/VL + AVX2 + FMA)".
std::string describe(IsaLevel level);

// The levels this build has kernels for, narrowest first.
std::vector<IsaLevel> compiled_isa_levels();
// Whether this CPU (and its operating system) can run the level.
bool cpu_supports(IsaLevel level);

// The choice rule: `requested` is CNCLAB_ISA's value (empty: unset); the
// widest compiled level that `supported` accepts, or the requested one when
// it is compiled and supported. Throws ConfigError otherwise.
IsaLevel choose_isa(std::string_view requested, const std::vector<IsaLevel>& compiled,
                    const std::function<bool(IsaLevel)>& supported);

// This process's level, chosen on the first call (choose_isa with CNCLAB_ISA
// and this CPU) and the same for the rest of the process. Throws ConfigError
// (every call) when CNCLAB_ISA cannot be honoured.
IsaLevel active_isa();

}  // namespace cnclab
