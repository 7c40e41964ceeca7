#pragma once
// One section of the contour-error feedrate job (feedrate_job.hpp): every
// tolerance's constrained plan and baselines, verified on the simulated
// machine, into the job's result record and per-tick file.
#include <functional>
#include <ostream>
#include <string>

#include "cnclab/experiment/run_record.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/studies/contour_error/feedrate_job.hpp"

namespace cnclab {

struct FeedrateSectionRun {
  const FeedrateJob& job;
  const PlanarPath& path;  // the section
  ContourPredictor& predictor;
  FeedrateOptimisationOptions optimisation;  // limits, grid and margins set; tolerance per run
  VerificationOptions verification;          // machine set; tolerance per run
  double contour_rms = 0.0;  // the predictor's own [mm]: tolerances below it are not planned
  std::string prefix;        // of metrics and facts ("" or "s03_")
  std::string group;         // in the per-tick file ("" or "s03/")
  std::function<void(const std::string&)> say;  // a progress line (may be empty)
};

// Runs every tolerance of the job on the section; metrics and facts into
// `rec`, series into `ticks`, a line per tolerance into `report`. Returns
// "<eps> uniform/constrained <ratio>; ..." for the summary line.
std::string run_feedrate_section(const FeedrateSectionRun& run, RunRecord& rec, H5File& ticks,
                                 std::ostream& report);

}  // namespace cnclab
