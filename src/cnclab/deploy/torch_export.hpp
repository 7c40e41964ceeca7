#pragma once
// A trained network as a Python file that loads in PyTorch as a
// torch.nn.Module (`cnclab export --format torch`): NAME.py, defining class
// NAME with the trained values as exact hex-float texts (float.fromhex),
// float64 by default (NAME(dtype=torch.float32) for float). It predicts as
// cnclab does, the normalisation inside, in the columns' own units
// (INPUT_COLUMNS, OUTPUT_COLUMNS name them):
//   mlp:  model(x)                x (batch, inputs) -> (batch, outputs)
//   narx: state = model.initial_state(batch)   standstill (NAME_init)
//         y, state = model(x, state)           one tick, x and y (batch, networks);
//                                              the delay lines are the explicit state
//         model.simulate(xs)                   (ticks, batch, networks) from standstill
// plus the methods a SequenceExtension adds (seed 002: contour_error).
#include <string>
#include <vector>

#include "cnclab/deploy/deployed_model.hpp"

namespace cnclab {

// `name`: the class and file name (a Python identifier, check_export_identifier).
std::string torch_export(const DeployedModel& model, const std::string& name,
                         const std::vector<std::string>& notes = {});

}  // namespace cnclab
