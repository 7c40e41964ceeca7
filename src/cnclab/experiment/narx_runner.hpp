#pragma once
// The pipeline of a narx experiment (model.type narx, narx_spec.hpp):
// dataset -> sequential halves -> per target one NARX network trained
// through trainer.stages on the first half -> closed-loop prediction of the
// second half from measured initial states -> registered sequence metrics
// (sequence_metrics.hpp) -> one result file (result_file.hpp, result_layout.hpp).
// run_experiment (runner.hpp) calls it for narx experiments.
#include "cnclab/experiment/runner.hpp"

namespace cnclab {

RunOutcome run_narx_experiment(const LoadedExperiment& experiment, const RunOptions& options);

}  // namespace cnclab
