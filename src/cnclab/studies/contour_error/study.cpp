#include "cnclab/studies/contour_error/study.hpp"

#include "cnclab/report/tables.hpp"
#include "cnclab/studies/contour_error/contour_error_tables.hpp"
#include "cnclab/studies/contour_error/narx_metrics.hpp"

namespace cnclab {
void register_contour_error_study() {
  register_contour_error_metrics();
  register_table(
      {"contour-error",
       "seed 002: NARX training methods, architecture sweep, contour-error estimates and the "
       "contour predictor's accuracy (simulated machine)",
       print_contour_error_tables, measure_contour_error_tables,
       "studies/contour_error_tables.yaml"});
}

}  // namespace cnclab
