#include "cnclab/experiment/spec_narx.hpp"

#include "cnclab/experiment/sequence_metrics.hpp"

namespace cnclab {

void read_narx_model_section(const ConfigReader& root, ExperimentSpec& spec) {
  if (spec.split.mode != SplitMode::sequential_halves) {
    root.section("split").fail(
        "mode",
        "must be sequential_halves for model.type narx (a time series is not shuffled: "
        "the first half trains, the second validates)");
  }
  if (spec.normalisation.inputs != Scaling::none || spec.normalisation.targets != Scaling::none) {
    root.section("normalisation")
        .fail("inputs",
              "must be none (inputs and targets) for model.type narx: the trial uses "
              "the dataset's own scaling (following_error: mapminmax by its generator)");
  }
  spec.narx = read_narx_model(root.section("model"));
  spec.metrics = sequence_metric_names();
}

void read_narx_trainer(const ConfigReader& root, ExperimentSpec& spec) {
  const ConfigReader trainer = root.section("trainer");
  if (trainer.has("type") || !trainer.has("stages")) {
    trainer.fail("stages", "model.type narx trains in stages: give trainer.stages, e.g. " +
                               stages_example() + ", and no trainer.type");
  }
  spec.stages = read_stages(trainer);
}

}  // namespace cnclab
