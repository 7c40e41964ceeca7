#pragma once
// Seed 000 Table 2 (dropout keep probability p against MSE): the single runs
// of each variant, and the table over the seed sweep of the manifest's `repeats:`
// (surface 1 over keep probabilities p and 1.0, no dropout): per p the test
// MSE's mean ± std over the seeds with the trained networks evaluated both
// ways (model.dropout.inference, nn/mlp.hpp): deterministically (one pass,
// r = 1) and by Monte-Carlo dropout (the mean of N masked passes). Each
// result holds both evaluations of its one training, so the two columns
// compare the same networks. The notes state a best p, and dropout against
// none, only as far as Welch's test over the seeds supports, under each
// evaluation (step_error_seed_notes.hpp).
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/report/text_table.hpp"
#include "cnclab/studies/step_error/step_error_study.hpp"

namespace cnclab {

// One evaluation's sentences: the lowest mean test MSE against the next
// lowest p, and no dropout (keep 1.0) against that p. `figure`:
// test_mse_deterministic or test_mse_mc (run_figures); `evaluation` names it.
std::vector<std::string> table2_seed_notes(const StepErrorRepeats& repeats,
                                           const std::string& figure,
                                           const std::string& evaluation);

// Table 2 of the single runs: per variant the test MSE of each p evaluated
// both ways, and the last training loss.
void print_table2(const StepErrorStudy& study, TableFormat format, std::ostream& out);

// The table over seeds; prints nothing when the study has no repeats.
void print_table2_over_seeds(const StepErrorStudy& study, TableFormat format, std::ostream& out);

}  // namespace cnclab
