#pragma once
// `cnclab tables feedrate`: the contour-error constrained feedrate over many
// sections declared up front (docs/motion.md, "Any path"): the planning
// predictor trained across feeds, its margins calibrated on held-out plans,
// on every declared section of its dataset path's validation half
// (experiments/contour_error/any_path/feedrate_sections.yaml) and of a path
// of another seed (feedrate_unseen_path.yaml). Per path and tolerance: the
// share of sections meeting the required share within eps_max, the median
// and worst share within, the median and worst ratio uniform slowdown /
// constrained, the oracle's median ratio (the ceiling of local feed limits)
// and the share of the oracle's median gain reached; then each section, the
// margins and the predictors compared on the held-out plans.
// `cnclab tables feedrate-example` is the earlier single section
// (feedrate_tables.hpp).
#include <ostream>

#include "cnclab/report/tables.hpp"

namespace cnclab {

void print_feedrate_sections_tables(const TablesOptions& options, std::ostream& out);
// The numbers the tables print, by name (targets in
// configs/studies/feedrate_tables.yaml), <path> = validation_path | unseen_path:
//   <path>.sections                       the sections run
//   <path>.sections_meeting_all           sections >= the required share at every tolerance
//   <path>.min_share_within               the worst share within over sections and tolerances
//   <path>.min_ratio_uniform_constrained  the worst uniform / constrained time ratio
//   <path>.min_oracle_gain_share          over the tolerances: (median ratio - 1) /
//                                         (oracle's median ratio - 1), 1 where the oracle
//                                         gains nothing and the plan loses nothing
//   <path>.<eps>.{sections_meeting, median_share_within, min_share_within,
//     median_ratio_uniform_constrained, min_ratio_uniform_constrained,
//     median_ratio_uniform_oracle, oracle_gain_share}
//   predictor.slowed_underprediction_p99_um, predictor.slowed_rms_um, predictor.max_margin_um
//   compared.<name>.slowed_underprediction_p99_um, compared.<name>.slowed_rms_um
//   predictor.lowest_slowed_rms   1 when no compared predictor has a lower slowed RMS
// A tolerance not planned on a section counts as 0 within and ratio NaN.
Measurements measure_feedrate_sections_tables(const TablesOptions& options);

}  // namespace cnclab
