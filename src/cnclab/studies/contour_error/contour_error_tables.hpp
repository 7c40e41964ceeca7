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

}  // namespace cnclab
