#pragma once
// Degenerate networks: outputs that do not follow their inputs (a dead ReLU
// layer, zero output weights, a collapsed training). Such a run is still a
// result (status complete) but carries the warning kConstantPredictions.
//
// The rule, per output row r of predictions ŷ and targets y (one sample per
// column, n columns), with the population variance var(v) = mean (v − v̄)²:
//   degenerate(r)  ⇔  n ≥ 2  and  ( max ŷ_r = min ŷ_r
//                                    or var(ŷ_r) < kConstantPredictionRatio · var(y_r) )
// The first clause catches exactly constant outputs even when the targets are
// constant too (var(y_r) = 0); the second, outputs whose spread is negligible
// next to the targets'. NaNs make neither clause true (a diverged run is
// flagged by its status instead).
#include <Eigen/Core>
#include <vector>

namespace cnclab {

inline constexpr double kConstantPredictionRatio = 1e-6;
inline constexpr const char* kConstantPredictions = "constant predictions";

// The output rows that are degenerate by the rule above, in row order.
// Throws cnclab::Error on mismatched shapes.
std::vector<Eigen::Index> constant_prediction_rows(const Eigen::MatrixXd& predictions,
                                                   const Eigen::MatrixXd& targets);

}  // namespace cnclab
