#include "cnclab/studies/step_error/study.hpp"

#include <memory>
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
  TableEntry tables{
      "step-error",
      "seed 000 Tables 2-8 (step-error BP network: dropout, surface 1, fine-tuning on surfaces 2 "
      "and 3, timing), ours vs paper, and the normaliser keep/refit comparison",
      print_step_error_tables,
      measure_step_error_tables,
      "studies/step_error_tables.yaml",
      step_error_experiment_files,
      {"step_error"}};
  // Loading is most of the cost (about 150 result files, the sweeps' plans):
  // once for both the tables and their targets.
  tables.load = [](const TablesOptions& options) {
    const auto study = std::make_shared<const StepErrorStudy>(load_step_error_study(options));
    return LoadedTables{
        [study, options](std::ostream& out) { print_step_error_study(*study, options, out); },
        [study] { return step_error_measures(*study); }};
  };
  register_table(std::move(tables));
}

}  // namespace cnclab
