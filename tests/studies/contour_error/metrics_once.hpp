#pragma once
// The seed-002 sequence metrics registered once per test process: a second
// registration is a std::logic_error, and gtest runs every test of the
// binary in one process when it is started directly (ctest starts one per
// test). In a header, since unity builds compile a target's tests in one
// file.
#include "cnclab/studies/contour_error/narx_metrics.hpp"

namespace cnclab::testing {

inline void register_contour_error_metrics_once() {
  static const bool done = [] {
    register_contour_error_metrics();
    return true;
  }();
  (void)done;
}

}  // namespace cnclab::testing
