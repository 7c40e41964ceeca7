#include "cnclab/experiment/job_kinds.hpp"

#include <cstdio>
#include <numbers>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/experiment/narx_job.hpp"
#include "cnclab/experiment/step_error_timing.hpp"
#include "cnclab/experiment/sweep_job.hpp"
#include "cnclab/experiment/trochoid_job.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// `kind: gcode` (trochoid_job.hpp). Takes seconds and writes text files:
// always re-run.
JobKind gcode_kind() {
  JobKind k;
  k.kind = "gcode";
  k.summary = "trochoidal groove tool path and ISO 6983 program (seed 004)";
  k.run = [](const fs::path& file, const JobContext& c) {
    const TrochoidJob job = load_trochoid_job(file, c.overrides, c.options.profile);
    const TrochoidFiles written = write_trochoid_outputs(job, c.options.results_dir);
    char detail[160];
    std::snprintf(detail, sizeof detail,
                  "%zu points; max radial engagement %.1f deg in the loops (slotting 180)",
                  written.outcome.groove.points.size(),
                  written.outcome.max_engagement_rad * 180.0 / std::numbers::pi);
    return JobReport{job.name,
                     "ran",
                     "gcode job (seconds; always re-run)",
                     detail,
                     written.program.string(),
                     "== " + job.name + " ==\n" + written.outcome.report};
  };
  k.resolved_yaml = [](const fs::path& file, const JobContext& c) {
    return to_yaml(load_trochoid_job(file, c.overrides, c.options.profile));
  };
  return k;
}

// `kind: sweep` (sweep_job.hpp): trials without a result run; a finished
// sweep with the same plan is reused.
JobKind sweep_kind() {
  JobKind k;
  k.kind = "sweep";
  k.summary =
      "a sweep of an experiment file, selecting the median repeat of its best point by the "
      "objective";
  k.run = [](const fs::path& file, const JobContext& c) {
    const SweepJob job = load_sweep_job(file, c.overrides, c.options.profile);
    const SweepJobOutcome r = run_sweep_job(job, c.options, c.log);
    if (r.stopped != 0) {
      throw Error(job.name + ": interrupted by signal " + std::to_string(r.stopped) +
                  "; finished trials are kept, run again to resume");
    }
    if (!r.state.selected) {
      throw Error(job.name + ": " + selection_line(r.state) + " (reasons in " +
                  (r.state.dir / "summary.h5").string() + ")");
    }
    JobReport report;
    report.name = job.name;
    report.action = r.ran == 0 ? "reused" : "ran";
    report.why = r.ran == 0 ? "sweep plan unchanged, every trial has a result"
                            : std::to_string(r.ran) + " trial(s) had no result";
    report.detail = selection_line(r.state);
    report.file = r.state.dir.string();
    return report;
  };
  k.resolved_yaml = [](const fs::path& file, const JobContext& c) {
    return to_yaml(load_sweep_job(file, c.overrides, c.options.profile));
  };
  return k;
}

// `kind: narx` (narx_job.hpp): seed 002's NARX studies; the result is
// reused while the resolved config is unchanged.
JobKind narx_kind() {
  JobKind k;
  k.kind = "narx";
  k.summary =
      "NARX following-error / contour-error study over methods, architectures, seeds (seed 002)";
  k.run = [](const fs::path& file, const JobContext& c) {
    const NarxJob job = load_narx_job(file, c.overrides, c.options.profile);
    const NarxJobOutcome o =
        run_narx_job(job, c.options.results_dir, c.options.datasets_dir, c.options.force, c.log);
    return JobReport{job.name,
                     o.reused ? "reused" : "ran",
                     o.reused
                         ? "config unchanged (hash " + job.config_hash + ")"
                         : (c.options.force ? "--force" : "no result for this resolved config"),
                     narx_summary_line(o.result),
                     o.file.string(),
                     ""};
  };
  k.resolved_yaml = [](const fs::path& file, const JobContext& c) {
    return load_narx_job(file, c.overrides, c.options.profile).resolved_yaml;
  };
  return k;
}

// `kind: step_error_timing` (step_error_timing.hpp): seed 000 Table 8. A
// measurement: re-run every time (results of a timing are not reusable).
JobKind step_error_timing_kind() {
  JobKind k;
  k.kind = "step_error_timing";
  k.summary = "seed 000 Table 8: geometric vs exact vs network step-error time";
  k.run = [](const fs::path& file, const JobContext& c) {
    const StepErrorTimingJob job = load_step_error_timing_job(file, c.overrides, c.options.profile);
    const StepErrorTimingResult result = run_step_error_timing(job, c.options.results_dir);
    const fs::path written = write_step_error_timing(result, c.options.results_dir);
    return JobReport{job.name,
                     "ran",
                     "timing job (a measurement; always re-run)",
                     step_error_timing_summary(result),
                     written.string(),
                     ""};
  };
  k.resolved_yaml = [](const fs::path& file, const JobContext& c) {
    return to_yaml(load_step_error_timing_job(file, c.overrides, c.options.profile));
  };
  return k;
}

std::string known_kinds() {
  std::string s = "train";
  for (const auto& k : builtin_job_kinds()) s += ", " + k.kind;
  return s;
}

}  // namespace

std::vector<JobKind> builtin_job_kinds() {
  return {gcode_kind(), sweep_kind(), narx_kind(), step_error_timing_kind()};
}

std::optional<JobKind> find_job_kind(const std::string& kind) {
  for (auto& k : builtin_job_kinds()) {
    if (k.kind == kind) return k;
  }
  return std::nullopt;
}

std::string experiment_kind(const fs::path& file) {
  const ConfigDocument doc = ConfigDocument::load(file);
  const ConfigReader root = doc.root();
  const auto kind = root.get<std::string>("kind", "train");
  if (kind != "train" && !find_job_kind(kind)) {
    root.fail("kind", "unknown kind; known: " + known_kinds());
  }
  return kind;
}

}  // namespace cnclab
