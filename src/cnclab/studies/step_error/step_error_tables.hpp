#pragma once
// `cnclab tables step-error`: seed 000 Tables 2-8 from the step-error study's
// results (the experiments listed in configs/studies/step_error_tables.yaml
// and the Table 8 timing job experiments/step_error/table8_timing.yaml),
// each beside the paper's numbers (results/reference/seed000_step_error.yaml),
// plus the normaliser keep/refit comparison the paper leaves open.
#include <ostream>

#include "cnclab/report/tables.hpp"
#include "cnclab/studies/step_error/step_error_study.hpp"

namespace cnclab {

// The tables of a loaded study (`options`: format, and where Table 8's job
// file is).
void print_step_error_study(const StepErrorStudy& study, const TablesOptions& options,
                            std::ostream& out);
// Loads the study (load_step_error_study) and prints it: TableEntry::print.
void print_step_error_tables(const TablesOptions& options, std::ostream& out);

}  // namespace cnclab
