#include "cli/builtins.hpp"

#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/studies/contour_error/study.hpp"
#include "cnclab/studies/five_axis/study.hpp"
#include "cnclab/studies/step_error/study.hpp"
#include "cnclab/sweep/sweep_job.hpp"

namespace cnclab {

// The order is the order `cnclab tables` lists tables and a bad `kind:`
// lists kinds: gcode, sweep, feedrate_optimisation, step_error_timing; ik,
// contour-error, feedrate, step-error.
void register_builtins() {
  register_five_axis_study();           // kind gcode, table ik
  register_job_kind(sweep_job_kind());  // kind sweep
  register_contour_error_study();  // kind feedrate_optimisation, tables contour-error, feedrate
  register_step_error_study();     // kind step_error_timing, table step-error
}

}  // namespace cnclab
