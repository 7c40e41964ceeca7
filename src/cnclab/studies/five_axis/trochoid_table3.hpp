#pragma once
// Seed 004's Table 3 ("Calculation of coordinates") against its Eq. 6: the
// transcribed points (results/reference/trochoid_table3.csv) checked for
// internal consistency and fitted with the trochoid family of
// kinematics/trochoid_fit.hpp; the report states which trochoid reproduces
// them (or that none does).
#include <filesystem>
#include <ostream>

namespace cnclab {

// Reads the CSV (t,x,y,line,coordinates; '#' comments) and prints the
// comparison; `groove_radius` is the R = (W - D)/2 of the groove being cut.
// Throws IoError naming the file and line on a missing or malformed file.
void compare_with_table3(const std::filesystem::path& csv, double groove_radius, std::ostream& out);

}  // namespace cnclab
