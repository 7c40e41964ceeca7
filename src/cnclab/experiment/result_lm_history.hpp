#pragma once
// The Levenberg-Marquardt part of a training history (the trainers that
// record one, train/trainer_registry.hpp history layout), as an
// MLP run's /history and each NARX stage's group hold it:
//   <group>/<series>            one value per epoch (kLmSeries)
//   <group> attrs initial_<series>   the state before the first step
// `curvature` and the initial_ attributes came later: files written before
// lack them and read as NaN / no initial state.
#include <cstddef>
#include <string>

#include "cnclab/io/h5.hpp"
#include "cnclab/train/summary.hpp"

namespace cnclab {

struct LmSeries {
  const char* name;
  double LmEpochRecord::*field;
  const char* units;
  bool required;  // false: absent in older files
};
inline constexpr LmSeries kLmSeries[] = {
    {"sse", &LmEpochRecord::sse, "normalised target units squared (E_D, sum)", true},
    {"ssw", &LmEpochRecord::ssw, "1 (E_W, sum of squared parameters)", true},
    {"alpha", &LmEpochRecord::alpha, "1", true},
    {"beta", &LmEpochRecord::beta, "1", true},
    {"gamma", &LmEpochRecord::gamma, "1 (effective number of parameters)", true},
    {"mu", &LmEpochRecord::mu, "1", true},
    {"gradient", &LmEpochRecord::gradient,
     "2 |J^T e| / N on an mse objective; 2 |J^T e| on an sse objective (Bayesian "
     "regularisation)",
     true},
    {"curvature", &LmEpochRecord::curvature, "1 (beta max_i (J^T J)_ii)", false},
};

void write_lm_history(H5File& f, const std::string& group, const Summary& s);
// Fills s.lm_history (`epochs` records) and s.lm_initial; IoError naming
// the file and dataset on a missing required series or a wrong length.
void read_lm_history(const H5File& f, const std::string& group, std::size_t epochs, Summary& s);

}  // namespace cnclab
