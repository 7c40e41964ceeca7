#pragma once
// Seed 000 Table 2 (dropout keep probability p against MSE): the single runs
// of each variant, and the table over the seed sweep of the manifest's
// `repeats:` (Table 2's keep probabilities and 1.0, no dropout, each over
// seeds). Table 2's runs hold a validation part out of the training part
// (configs/splits/step_error_table2.yaml): p is chosen on validation and the
// test MSE is reported after the choice; the lowest test MSE (the paper's
// own reading, which chooses on the data it reports) is shown beside it,
// never used. Every trained network is evaluated both ways
// (model.dropout.inference, nn/mlp.hpp): deterministically (one pass, r = 1)
// and by Monte-Carlo dropout (the mean of N masked passes), from one
// training, so the two compare the same networks; each evaluation chooses p
// on its own validation MSE. The notes over seeds state a best p, and
// dropout against none, only as far as Welch's test supports
// (step_error_seed_notes.hpp).
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/report/text_table.hpp"
#include "cnclab/studies/step_error/step_error_study.hpp"

namespace cnclab {

// One evaluation's sentences over the seeds of Table 2's sweep: the lowest
// mean validation MSE against the next (the choice of p), the chosen p's test
// MSE (reported after), no dropout (keep 1.0) against the chosen p on each
// split, and the choice on test beside it. `suffix`: "_deterministic" or
// "_mc" (run_figures' validation_mse<suffix>, test_mse<suffix>);
// `evaluation` names it.
std::vector<std::string> table2_seed_notes(const StepErrorRepeats& repeats,
                                           const std::string& suffix,
                                           const std::string& evaluation);

// Table 2 of the single runs: per variant the validation and test MSE of each
// p evaluated deterministically, the test MSE by MC dropout, and the last
// training loss.
void print_table2(const StepErrorStudy& study, TableFormat format, std::ostream& out);

// The table over seeds; prints nothing when the study has no repeats.
void print_table2_over_seeds(const StepErrorStudy& study, TableFormat format, std::ostream& out);

}  // namespace cnclab
