#pragma once
// model: {type: narx, ...} and trainer: {stages: [...]} of a `kind: train`
// experiment: one SISO NARX network (nn/narx.hpp, seed 002 Eq. 1) per
// target, trained in stages (seed 002 Sec. II).
//
//   model:
//     type: narx
//     hidden: 12              # H, tanh units (seed 002: 12)
//     activation: tanh
//     input_delays: 4         # D_V, velocity inputs v(t - d0 - j), j < D_V
//     feedback_delays: 4      # D_E, fed-back errors e(t-1..t-D_E)
//     first_input_delay: 0    # d0: 0 = Eq. 1 with v(t); 1 = MATLAB narxnet(1:D_V, ...)
//     inputs: [v, direction]  # optional: each network's input channels (below)
//   trainer:
//     stages:                 # run in order, each from the previous stage's weights
//       - {mode: open_loop, type: TRAINER, epochs: 150, min_gradient: 1.0e-8}
//       - {mode: closed_loop, type: TRAINER, epochs: 40, min_gradient: 1.0e-8}
//
// mode open_loop: series-parallel (the measured errors are fed back: a static
// network on the regressors); closed_loop: parallel (the network's own
// predictions are fed back; exact dynamic Jacobian by RTRL). Each stage takes
// the keys of its `type` (trainer_spec.hpp: a trainer that needs a Jacobian). Seed 002's three
// training methods are three stage lists: [open_loop, closed_loop] (its
// two-stage method), [open_loop], [closed_loop].
//
// Target k is predicted from input k of the dataset (following_error: e_x
// from v_x, e_y from v_y); its network's weights are drawn from the stream
// "narx/init/<axis>" of the master seed, <axis> the target name after its
// last '_' (e_x -> x). With `inputs` (names before the axis suffix), the
// network of axis a takes the dataset inputs <name>_a in that order as its
// channels (inputs: [v, direction]: e_x from v_x and direction_x; the
// following_error generator's extra_inputs, data/following_error.hpp).
#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/experiment/trainer_spec.hpp"
#include "cnclab/nn/narx.hpp"

namespace cnclab {

template <class S>
class FieldList;

// The `model:` keys of type narx, as YAML holds them.
struct NarxModelSpec {
  std::size_t hidden = 12;
  std::string activation = "tanh";
  std::size_t input_delays = 4;
  std::size_t feedback_delays = 4;
  std::size_t first_input_delay = 0;
  // Input channel names without the axis suffix; empty: input k for target k.
  std::vector<std::string> inputs;

  // The network's options (initialisers: NarxOptions' defaults, U(-0.5, 0.5)).
  NarxOptions options() const;
};
const FieldList<NarxModelSpec>& narx_model_fields();

enum class StageMode { open_loop, closed_loop };
std::string to_string(StageMode mode);

struct TrainingStage {
  StageMode mode = StageMode::open_loop;
  TrainerSpec trainer;  // a trainer that needs_jacobian (read_stages)
  // closed_loop: the series is predicted in windows of `horizon` steps, each
  // started from measured states (NarxClosedLoopObjective); 0 = one window,
  // the whole series (seed 002's parallel training).
  std::size_t horizon = 0;
  // closed_loop on the whole series: when the stage stops on mu_max or
  // diverges, it is trained again from its starting weights, first on
  // windows of this many steps, then on the whole series (the stage's epochs
  // each), and the weights with the lower whole-series SSE are kept
  // (docs/narx_training.md). 0: no second try.
  std::size_t fallback_horizon = 0;
};

// One stage's own keys besides its trainer's.
struct StageHead {
  std::string mode = "open_loop";
  std::size_t horizon = 0;
  std::size_t fallback_horizon = 0;
};
const FieldList<StageHead>& stage_fields();

// "model.type" of a model section: "mlp" (the default) or "narx";
// ConfigError for anything else.
std::string read_model_type(const ConfigReader& model);
// The narx model section (type already read); validated.
NarxModelSpec read_narx_model(const ConfigReader& model);
// The model section as resolved: {type: narx, hidden, ...}.
YAML::Node narx_model_to_node(const NarxModelSpec& model);

// trainer.stages: a non-empty list of maps; each one's keys are checked
// strictly (unknown keys are ConfigErrors naming trainer.stages[i]).
std::vector<TrainingStage> read_stages(const ConfigReader& trainer);
// The trainer section with stages: {stages: [{mode, type, ...}, ...]}, each
// stage a flow map of every option resolved.
YAML::Node stages_to_node(const std::vector<TrainingStage>& stages);

// "open_loop:TYPE+closed_loop:TYPE" (each stage's mode and trainer type),
// for messages and result files.
std::string stages_text(const std::vector<TrainingStage>& stages);

// An example trainer.stages for messages and the schema: an open-loop then a
// closed-loop stage, "type: TRAINER" with the trainers a stage takes (those
// that need a Jacobian, from the registry) listed after it.
std::string stages_example();

}  // namespace cnclab
