#pragma once
// Seed 000 Table 8 for `cnclab tables step-error`: the timing job's result
// (step_error_timing.hpp, found through the result store for the job file
// experiments/step_error/table8_timing.yaml and the profile) beside the
// paper's seconds. A missing timing result prints a one-line note naming the
// command that makes it instead of the table.
#include <ostream>

#include "cnclab/report/tables.hpp"
#include "cnclab/studies/step_error/step_error_study.hpp"

namespace cnclab {

void print_step_error_table8(const StepErrorStudy& study, const TablesOptions& options,
                             std::ostream& out);

}  // namespace cnclab
