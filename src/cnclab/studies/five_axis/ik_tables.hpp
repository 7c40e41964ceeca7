#pragma once
// `cnclab tables ik`: seed 004 Table 5 from the five axis experiments
// (experiments/ik/ik_{x,y,z,a,c}.yaml) beside the paper's numbers
// (results/reference/ik_table5.yaml), and - beyond the paper - the
// machine-space error of the predicted joint sets through forward kinematics.
#include <ostream>

#include "cnclab/report/tables.hpp"

namespace cnclab {

void print_ik_tables(const TablesOptions& options, std::ostream& out);

}  // namespace cnclab
