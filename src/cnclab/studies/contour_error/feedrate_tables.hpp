#pragma once
// `cnclab tables feedrate`: the contour-error feedrate job's result
// (experiments/contour_error/feedrate.yaml, feedrate_job.hpp) per tolerance
// and method: traversal time, maximum simulated contour error, share of
// ticks within eps_max, and the ratio uniform slowdown / constrained.
#include <ostream>

#include "cnclab/report/tables.hpp"

namespace cnclab {

void print_feedrate_tables(const TablesOptions& options, std::ostream& out);
// "<eps label>.<method>.time_s" etc. and "<eps label>.ratio_uniform_constrained".
Measurements measure_feedrate_tables(const TablesOptions& options);

}  // namespace cnclab
