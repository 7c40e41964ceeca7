#pragma once
// Seed 000 (step error): the `kind: step_error_timing` job and `cnclab
// tables step-error`, registered by the CLI (src/cli/builtins.cpp).
namespace cnclab {
void register_step_error_study();
}  // namespace cnclab
