#pragma once
// A trained network applied to an input (prediction_input.hpp), as cnclab
// computes it in training: the same network code (nn/mlp.hpp, nn/narx.hpp)
// and the stored normalisation, so on the result's own split the
// predictions are the ones the result stores.
//
// Output columns, a value per sample of the input (in the order read):
//   sample                        the sample's index in the input
// mlp, per target T (unit of the dataset):
//   T.predicted, T.measured (when the input has T)
// narx, per network with target T in the dataset's units and, where the
// model has physical columns, P (e.g. e_ref_x [µm]) the same in physical units:
//   T.closed_loop, P.closed_loop  the network's own predictions fed back
//                                 (seed 002's parallel configuration)
//   T.open_loop, P.open_loop      the measured values fed back
//                                 (series-parallel), when the input has them
//   T.measured, P.measured
// and the columns a SequenceExtension computes per tick (seed 002: the
// Taylor contour error of the closed-loop, open-loop and measured errors).
//
// narx initial states: `measured` (the default when the input has the
// targets) starts the closed loop from the first first_step() measured
// values, which the first rows then repeat, as the result's stored
// validation prediction; `rest` starts from standstill (every past input and
// output the physical 0: NarxPredictor::reset, an export's NAME_init), and
// every row is a prediction.
#include <cstddef>
#include <string>
#include <vector>

#include "cnclab/deploy/deployed_model.hpp"
#include "cnclab/deploy/named_column.hpp"
#include "cnclab/deploy/prediction_input.hpp"

namespace cnclab {

enum class InitialState { automatic, measured, rest };
// ConfigError naming --initial unless "measured" or "rest".
InitialState parse_initial_state(const std::string& text);

struct PredictOptions {
  // all | train | validation | test: the part of the result's own split
  // (the input must be its training dataset). narx: the halves; a part's
  // closed loop starts from its own first samples.
  std::string split = "all";
  InitialState initial = InitialState::automatic;  // narx (see above)
};

struct Prediction {
  std::vector<NamedColumn> columns;
  std::size_t samples = 0;
  std::size_t first_step = 0;      // leading rows that repeat measured initial states
  std::string initial_state;       // narx: "measured" or "rest"; mlp: ""
  std::vector<std::string> notes;  // one line each: columns used, what was left out and why
};

// ConfigError (exit 2) with the reason, before any work: columns missing
// (a wrong width) or in other units, a dataset of another generator,
// columns a CSV has that the model does not read, a split of another
// dataset, too few samples for the delays.
Prediction predict(const DeployedModel& model, const PredictionInput& input,
                   const PredictOptions& options = {});

}  // namespace cnclab
