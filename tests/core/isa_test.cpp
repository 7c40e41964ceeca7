// The instruction-set level rule (core/isa.hpp) with a stand-in CPU: the
// widest compiled level it supports, CNCLAB_ISA's level when it can run, and
// a ConfigError naming CNCLAB_ISA otherwise.
#include "cnclab/core/isa.hpp"

#include <gtest/gtest.h>

#include <string>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

const std::vector<IsaLevel> kAll = {IsaLevel::baseline, IsaLevel::v3, IsaLevel::v4};

std::string error_of(std::string_view requested, const std::vector<IsaLevel>& compiled,
                     IsaLevel widest) {
  try {
    choose_isa(requested, compiled, [&](IsaLevel l) { return l <= widest; });
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Isa, TheWidestSupportedLevelUnlessOneIsRequested) {
  const auto upto = [](IsaLevel widest) { return [=](IsaLevel l) { return l <= widest; }; };
  EXPECT_EQ(choose_isa("", kAll, upto(IsaLevel::v4)), IsaLevel::v4);
  EXPECT_EQ(choose_isa("", kAll, upto(IsaLevel::v3)), IsaLevel::v3);
  EXPECT_EQ(choose_isa("", kAll, upto(IsaLevel::baseline)), IsaLevel::baseline);
  EXPECT_EQ(choose_isa("baseline", kAll, upto(IsaLevel::v4)), IsaLevel::baseline);
  EXPECT_EQ(choose_isa("v3", kAll, upto(IsaLevel::v4)), IsaLevel::v3);
  EXPECT_EQ(choose_isa("", {IsaLevel::native}, upto(IsaLevel::native)), IsaLevel::native);
}

TEST(Isa, UnknownUnsupportedOrUncompiledLevelsAreClearErrors) {
  EXPECT_EQ(error_of("v9", kAll, IsaLevel::v4),
            "CNCLAB_ISA=v9: unknown level; this build has: baseline, v3, v4");
  EXPECT_EQ(error_of("v4", kAll, IsaLevel::v3),
            "CNCLAB_ISA=v4: this CPU does not support v4 (x86-64-v4: AVX-512 F/CD/BW/DQ/VL + "
            "AVX2 + FMA); unset CNCLAB_ISA to use the widest level it supports");
  EXPECT_EQ(error_of("v3", {IsaLevel::native}, IsaLevel::native),
            "CNCLAB_ISA=v3: this build has no kernels for it (it has: native)");
}

TEST(Isa, ThisProcessRunsACompiledLevelThisCpuSupports) {
  const IsaLevel l = active_isa();
  const auto compiled = compiled_isa_levels();
  EXPECT_NE(std::find(compiled.begin(), compiled.end(), l), compiled.end());
  EXPECT_TRUE(cpu_supports(l));
  EXPECT_EQ(active_isa(), l);  // chosen once
  EXPECT_TRUE(cpu_supports(IsaLevel::baseline));
  // v4 implies v3 on any CPU.
  if (cpu_supports(IsaLevel::v4)) {
    EXPECT_TRUE(cpu_supports(IsaLevel::v3));
  }
}

}  // namespace
}  // namespace cnclab
