#pragma once
// `cnclab tables step-error`: seed 000 Tables 2-8 from the step-error study's
// results (the experiments listed in configs/studies/step_error_tables.yaml
// and the Table 8 timing job experiments/step_error/table8_timing.yaml),
// each beside the paper's numbers (results/reference/seed000_step_error.yaml),
// plus the normaliser keep/refit comparison the paper leaves open.
#include <ostream>

#include "cnclab/report/tables.hpp"

namespace cnclab {

void print_step_error_tables(const TablesOptions& options, std::ostream& out);

}  // namespace cnclab
