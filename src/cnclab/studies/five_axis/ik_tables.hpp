#pragma once
// `cnclab tables ik`: seed 004 Table 5 from the five axis experiments
// (experiments/ik/ik_{x,y,z,a,c}.yaml) beside the paper's numbers
// (results/reference/ik_table5.yaml), and - beyond the paper - the
// machine-space error of the predicted joint sets through forward kinematics.
#include <ostream>

#include "cnclab/report/tables.hpp"

namespace cnclab {

void print_ik_tables(const TablesOptions& options, std::ostream& out);

// The numbers Table 5 and the machine-unit table print, by name
// (TableEntry::measure; targets in configs/studies/ik_tables.yaml):
//   <variant>.<axis>.{training_set, test_set, validation_set}   split sizes
//   <variant>.<axis>.{mse_validation, mse_test}                 normalised units
//   <variant>.<axis>.{rmse, max_abs_error}                      mm (X, Y, Z), deg (A, C)
// variant: sgdm (the paper's settings), search, trainbr; axis: X, Y, Z, A, C
// (search and trainbr where their results exist).
Measurements measure_ik_tables(const TablesOptions& options);

}  // namespace cnclab
