#pragma once
// Seed 002 (contour error): the NARX sequence metrics and `cnclab tables
// contour-error`, registered by the CLI (src/cli/builtins.cpp).
namespace cnclab {
void register_contour_error_study();
}  // namespace cnclab
