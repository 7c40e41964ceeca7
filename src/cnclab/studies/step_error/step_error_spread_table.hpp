#pragma once
// The seed-to-seed spread of the step-error study's headline rows (the manifest's `repeats:`,
// step_error_repeats.hpp): one table with, per row, the paper's single number, our run that Tables
// 3-7 show, and the mean ± std over the seed sweep; and the notes that compare settings only as far
// as Welch's test supports (step_error_seed_notes.hpp). Table 2 over the seeds has its own table
// (step_error_table2.hpp).
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/report/text_table.hpp"
#include "cnclab/studies/step_error/step_error_study.hpp"

namespace cnclab {

// Keep vs refit at 15 %, mean |e| per surface.
std::vector<std::string> normaliser_seed_notes(const StepErrorRepeats& repeats);

// The table; prints nothing when the study has no repeats.
void print_step_error_spread(const StepErrorStudy& study, TableFormat format, std::ostream& out);

}  // namespace cnclab
