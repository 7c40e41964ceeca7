#include "cnclab/studies/contour_error/study.hpp"

#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/report/tables.hpp"
#include "cnclab/studies/contour_error/contour_error_tables.hpp"
#include "cnclab/studies/contour_error/narx_job.hpp"
#include "cnclab/studies/contour_error/narx_metrics.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

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

}  // namespace

void register_contour_error_study() {
  register_contour_error_metrics();
  register_job_kind(narx_kind());
  register_table(
      {"contour-error",
       "seed 002: NARX training methods, architecture sweep, contour-error estimates and the "
       "contour predictor's accuracy (simulated machine)",
       print_contour_error_tables});
}

}  // namespace cnclab
