#pragma once
// The runs of one of seed 002's NARX studies, as the contour-error tables
// read them: the complete trials of a `kind: sweep` file over
// experiments/contour_error/narx.yaml (training_methods.yaml,
// architecture.yaml), each a standard result file with the sequence metrics
// of studies/contour_error/narx_metrics.hpp.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/report/tables.hpp"

namespace cnclab {

// One trial: what it trained and its metrics.
struct NarxStudyRun {
  // From trainer.stages: two_stage (open_loop then closed_loop),
  // open_loop_only, closed_loop_only, "_windowed" when a closed_loop stage
  // has a horizon, "_retry" when one has a fallback_horizon; else the modes
  // joined by '+'.
  std::string method;
  std::size_t hidden = 0, input_delays = 0, feedback_delays = 0;
  std::uint64_t seed = 0;
  std::size_t open_epochs = 0, closed_epochs = 0;  // the first network's, per mode
  std::size_t second_tries = 0;  // networks whose stage was tried again (fallback_horizon)
  std::string stops;             // "x: max_epochs, y: mu_max": how each network's last stage ended
  // narx_metrics.hpp names ("contour_rms", stored as validation.contour_rms:
  // the validation half), µm.
  std::map<std::string, double> metrics;
  bool bounded() const;  // metric "stable" is 1: the prediction stayed bounded
};

// The criterion for a stable run (docs/narx_training.md), stricter than bounded: a bounded
// prediction, and on every axis a closed-loop RMS within kStableFactor times
// the best bounded run's of the same study. A network that does not blow up
// but predicts 10x worse than the others is a failed training, as seed 002
// counts "large prediction errors" with the unstable runs (Sec. II).
inline constexpr double kStableFactor = 3.0;

struct NarxStudyRuns {
  std::string profile;            // the tables' --profile the runs were loaded with
  std::vector<std::string> axes;  // network axes of the first run (x, y)
  std::size_t train_samples = 0, validation_samples = 0;
  std::vector<NarxStudyRun> runs;              // plan order
  std::vector<std::filesystem::path> sources;  // the result files read
  std::vector<std::string> configs;            // their resolved configs (the settings notes)
  std::size_t trials = 0;                      // planned; runs.size() completed
  // One line per trial that ran and did not complete: "trial <id> (key=value
  // ..., seed S): failed: <reason>". The tables print them as notes, so a
  // mean over 4 runs is never read as a mean over the 5 planned.
  std::vector<std::string> not_completed;
  // The sweep's choice: the median repeat of its best point by `objective`
  // (sweep_summary.hpp), an index into `runs`; nullopt when none completed.
  // The objective is of the validation half, the half the tables report:
  // seed 002's sequential halves have no test part.
  std::optional<std::size_t> chosen;
  std::string objective;  // the sweep's objective metric (validation.contour_rms)
  double metric(const std::string& name) const;  // of the first run (dataset-level numbers)
  bool stable(const NarxStudyRun& run) const;    // kStableFactor criterion above
};

// The complete trials of experiments/contour_error/<file> under the tables'
// results folder and profile. MissingResults naming the command that makes
// them while any trial has not run; trials that ran and failed are left out
// of `runs` and listed in `not_completed`.
NarxStudyRuns load_narx_study(const TablesOptions& options, const std::string& file);

}  // namespace cnclab
