#pragma once
// `cnclab tables feedrate-example`: the contour-error feedrate job's result
// on its one section (experiments/contour_error/feedrate.yaml,
// feedrate_job.hpp), a section chosen by its outcome and labelled so (the
// study over declared sections: feedrate_sections_tables.hpp), per tolerance
// and method: traversal time, maximum simulated contour error, share of
// ticks within eps_max, and the ratio uniform slowdown / constrained.
#include <ostream>

#include "cnclab/report/tables.hpp"

namespace cnclab {

void print_feedrate_example_tables(const TablesOptions& options, std::ostream& out);
// The numbers the table prints, by name (targets in
// configs/studies/feedrate_example_tables.yaml):
//   <eps label>.<method>.{time_s, max_um, share_within}, <eps label>.ratio_uniform_constrained
//   constrained.min_share_within        the smallest share within eps_max over the tolerances
//   min_ratio_uniform_constrained       the smallest uniform / constrained time ratio
// (a tolerance that was not planned makes the first two NaN).
Measurements measure_feedrate_example_tables(const TablesOptions& options);

}  // namespace cnclab
