#pragma once
// Warnings a complete result carries: it is a result (status complete) but
// not a useful one. Stored in the result file as the root attribute
// `warnings` ("; "-separated, absent when none: older files read as none).
// Besides the ones below, the runner adds "constant targets (NAME)" when the
// dataset's targets have no spread to learn (data/constant_targets.hpp).
#include <string>
#include <vector>

#include "cnclab/experiment/run_record.hpp"

namespace cnclab {

// The warnings of a finished run, from its stored predictions: "constant
// predictions" when an output is degenerate by the rule of
// nn/constant_predictions.hpp (mlp: the test split; narx: the closed-loop
// validation part after the measured initial states). With several outputs
// the degenerate ones are named: "constant predictions (e_y)".
std::vector<std::string> prediction_warnings(const RunRecord& record);

// "complete", or "complete; warning: constant predictions" (show, compare).
std::string status_text(const std::string& status, const std::vector<std::string>& warnings);

// The stored form and back ("; "-separated; "" = none).
std::string join_warnings(const std::vector<std::string>& warnings);
std::vector<std::string> split_warnings(const std::string& text);

}  // namespace cnclab
