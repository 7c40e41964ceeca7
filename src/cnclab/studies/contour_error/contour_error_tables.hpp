#pragma once
// `cnclab tables contour-error`: seed 002's NARX studies (the sweeps
// experiments/contour_error/training_methods.yaml and architecture.yaml over
// narx.yaml, narx_study_runs.hpp) - the training-method table, the
// architecture sweep, the contour-estimate comparison and the contour
// predictor's accuracy, beside what the paper states
// (results/reference/seed002_contour_error.yaml; the paper prints no
// numeric table, its numbers are in the text).
#include <ostream>

#include "cnclab/report/tables.hpp"

namespace cnclab {

void print_contour_error_tables(const TablesOptions& options, std::ostream& out);

// The numbers the tables print, by name (TableEntry::measure; targets in
// configs/studies/contour_error_tables.yaml):
//   training_methods.<method>.{runs, stable_runs, bounded_runs}
//   training_methods.<method>.{rms_<axis>, max_<axis>, contour_rms}_{mean, std}   [µm]
//   training_methods.second_tries, training_methods.zero_rms_<axis>
//   estimates.<taylor|tangent|osculating>.{mean_abs_diff, max_abs_diff}           [µm]
//   architecture.h<H>_d<in>_<fb>.* and architecture.all.* as for a method
// (architecture.* only when the architecture sweep has results).
Measurements measure_contour_error_tables(const TablesOptions& options);

}  // namespace cnclab
