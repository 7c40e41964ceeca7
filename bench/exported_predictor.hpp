#pragma once
// The contour predictor as `cnclab export --format c` writes it (seed 002's
// two NARX networks plus the Taylor estimate), compiled here with the C
// compiler and flags of this build into a shared object, loaded and timed
// per 1 ms tick on the same series as the internal ContourPredictor; its
// allocations counted while it runs, and its imports listed.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "cnclab/motion/planar_path.hpp"
#include "cnclab/nn/narx_predictor.hpp"

namespace cnclab::bench {

struct ExportedTiming {
  double tick_seconds = 0;           // median CPU time per tick: both axes + the contour estimate
  double max_error_diff = 0;         // max |e_C - e_internal| [um] over the series
  double max_contour_diff = 0;       // max ||eps|_C - |eps|_internal| [um]
  long allocations = -1;             // heap allocations during the timed ticks (-1: not counted)
  std::vector<std::string> imports;  // the shared object's undefined symbols (nm -D -u)
  std::string compile;               // the compiler command
};

// models[0], models[1]: the x and y networks (errors in mm, as the internal
// predictor takes them; the export predicts um). velocity[t], reference[t]:
// the series. Throws cnclab::Error when the export does not compile or load.
ExportedTiming time_exported_predictor(const NarxAxisModel (&models)[2],
                                       const std::vector<Vec2>& velocity,
                                       const std::vector<PathPoint>& reference, int repeats);

// Heap allocations so far (malloc and friends, counted where this binary
// interposes them; -1 in sanitizer builds, where the sanitizer owns malloc).
long allocation_count();

}  // namespace cnclab::bench
