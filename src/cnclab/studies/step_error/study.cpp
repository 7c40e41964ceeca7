#include "cnclab/studies/step_error/study.hpp"

#include <nlohmann/json.hpp>

#include "cnclab/core/field_schema.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/report/tables.hpp"
#include "cnclab/studies/step_error/step_error_measures.hpp"
#include "cnclab/studies/step_error/step_error_study.hpp"
#include "cnclab/studies/step_error/step_error_tables.hpp"
#include "cnclab/studies/step_error/step_error_timing.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// `kind: step_error_timing` (step_error_timing.hpp): seed 000 Table 8. A
// measurement: re-run every time; the standard result it writes (named by
// the resolved job) is what Table 8 reads.
JobKind step_error_timing_kind() {
  const auto run = [](const StepErrorTimingJob& job, const JobContext& c) {
    const StepErrorTimingResult result = run_step_error_timing(job, c.options.results_dir);
    const fs::path written =
        write_step_error_timing(job, result, ResultStore(c.options.results_dir, c.options.profile));
    return JobReport{job.name,
                     "ran",
                     "timing job (a measurement; always re-run)",
                     step_error_timing_summary(result),
                     written.string(),
                     ""};
  };
  JobKind kind = job_kind("step_error_timing",
                          "seed 000 Table 8: geometric vs exact vs network step-error time",
                          load_step_error_timing_job, run);
  kind.schema = [] {
    return object_schema(step_error_timing_file_fields(),
                         "kind step_error_timing: seed 000 Table 8's timing");
  };
  return kind;
}

}  // namespace

void register_step_error_study() {
  register_job_kind(step_error_timing_kind());
  register_table(
      {"step-error",
       "seed 000 Tables 2-8 (step-error BP network: dropout, surface 1, fine-tuning on surfaces 2 "
       "and 3, timing), ours vs paper, and the normaliser keep/refit comparison",
       print_step_error_tables,
       measure_step_error_tables,
       "studies/step_error_tables.yaml",
       step_error_experiment_files,
       {"step_error"}});
}

}  // namespace cnclab
