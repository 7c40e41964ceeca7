#pragma once
// How an MLP run's network was evaluated (model.dropout.inference, nn/mlp.hpp)
// and, for a network with dropout, its evaluation the other way
// (RunRecord::other_inference), in the result file:
//   /model attrs dropout_inference, dropout_mc_samples
//   /other_inference attrs inference, mc_samples, one number per metric;
//   /other_inference/test_predictions (target units)
// Files written before these lack them: deterministic, no other evaluation.
#include <map>
#include <ostream>
#include <string>

#include "cnclab/experiment/run_record.hpp"
#include "cnclab/io/h5.hpp"

namespace cnclab {

void write_inference(H5File& f, const RunRecord& r);
// Fills r.model's dropout_inference and dropout_mc_samples and
// r.other_inference; IoError naming the file on an unknown inference name.
void read_inference(const H5File& f, RunRecord& r);

// `show`'s lines: the inference of the metrics above, and the other
// evaluation's metrics, when the network has dropout.
void print_inference(const RunRecord& r, std::ostream& out);

// The test predictions of `r` evaluated by `inference`: its own when that is
// its model.dropout.inference or its network has no dropout (both ways are
// then the same), the other evaluation's when stored; nullptr otherwise (a
// result written before the other evaluation was stored).
const Eigen::MatrixXd* test_predictions_by(const RunRecord& r, DropoutInference inference);
// The metrics ("<split>.<base>", nn/metrics.hpp) of `r` evaluated by
// `inference`, by the same rule; nullptr when not stored.
const std::map<std::string, double>* metrics_by(const RunRecord& r, DropoutInference inference);

}  // namespace cnclab
