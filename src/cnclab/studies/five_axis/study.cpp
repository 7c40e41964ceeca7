#include "cnclab/studies/five_axis/study.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>
#include <numbers>

#include "cnclab/core/field_schema.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/report/tables.hpp"
#include "cnclab/studies/five_axis/ik_runs.hpp"
#include "cnclab/studies/five_axis/ik_tables.hpp"
#include "cnclab/studies/five_axis/trochoid_job.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// `kind: gcode` (trochoid_job.hpp). Takes seconds and writes text files:
// always re-run.
JobKind gcode_kind() {
  const auto run = [](const TrochoidJob& job, const JobContext& c) {
    const TrochoidFiles written = write_trochoid_outputs(job, c.options.results_dir);
    char detail[160];
    std::snprintf(detail, sizeof detail,
                  "%zu points; max radial engagement %.1f deg in the loops (slotting 180)",
                  written.outcome.groove.points.size(),
                  written.outcome.max_engagement_rad * 180.0 / std::numbers::pi);
    return JobReport{job.name,
                     "ran",
                     "gcode job (seconds; always re-run)",
                     std::string(detail) + "; program " + written.program.string(),
                     written.result.string(),
                     "== " + job.name + " ==\n" + written.outcome.report};
  };
  JobKind kind = job_kind("gcode", "trochoidal groove tool path and ISO 6983 program (seed 004)",
                          load_trochoid_job, run);
  kind.schema = [] {
    return object_schema(trochoid_file_fields(),
                         "kind gcode: a trochoidal groove and its G-code program");
  };
  return kind;
}

}  // namespace

void register_five_axis_study() {
  register_job_kind(gcode_kind());
  register_table(
      {"ik",
       "seed 004 Table 5 (IK networks per axis, ours vs paper) and the machine-space error of the "
       "predicted joints",
       print_ik_tables, measure_ik_tables, "studies/ik_tables.yaml", ik_experiment_files});
}

}  // namespace cnclab
