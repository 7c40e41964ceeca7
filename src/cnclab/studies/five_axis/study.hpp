#pragma once
// Seed 004 (5-axis TTTRR): the `kind: gcode` job and `cnclab tables ik`,
// registered by the CLI (src/cli/builtins.cpp).
namespace cnclab {
void register_five_axis_study();
}  // namespace cnclab
