#include "cnclab/studies/contour_error/study.hpp"

#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/report/tables.hpp"
#include "cnclab/studies/contour_error/contour_deployment.hpp"
#include "cnclab/studies/contour_error/contour_error_tables.hpp"
#include "cnclab/studies/contour_error/feedrate_job.hpp"
#include "cnclab/studies/contour_error/feedrate_sections_tables.hpp"
#include "cnclab/studies/contour_error/feedrate_tables.hpp"
#include "cnclab/studies/contour_error/narx_metrics.hpp"

namespace cnclab {
void register_contour_error_study() {
  register_contour_error_metrics();
  register_contour_deployment();  // predict and export of its narx networks
  register_job_kind(feedrate_job_kind());
  register_table(
      {"contour-error",
       "seed 002: NARX training methods, architecture sweep, contour-error estimates and the "
       "contour predictor's accuracy (simulated machine)",
       print_contour_error_tables,
       measure_contour_error_tables,
       "studies/contour_error_tables.yaml",
       [](const TablesOptions& o) {
         return std::vector<std::filesystem::path>{
             o.experiment_file("contour_error/training_methods.yaml"),
             o.experiment_file("contour_error/architecture.yaml")};
       },
       {"contour_error", "narx_training"}});
  register_table({"feedrate",
                  "seed 002's application on any path: the contour-error constrained feedrate "
                  "with the planning predictor and calibrated margins on many declared sections "
                  "of two paths, vs the uniform slowdown and the oracle (simulated machine)",
                  print_feedrate_sections_tables, measure_feedrate_sections_tables,
                  "studies/feedrate_tables.yaml", [](const TablesOptions& o) {
                    return std::vector<std::filesystem::path>{
                        o.experiment_file("contour_error/any_path/feedrate_sections.yaml"),
                        o.experiment_file("contour_error/any_path/feedrate_unseen_path.yaml")};
                  }});
  register_table({"feedrate-example",
                  "seed 002's application on one section chosen by its outcome: contour-error "
                  "constrained feedrate vs the unconstrained plan, the uniform slowdown and the "
                  "best constant feed (simulated machine)",
                  print_feedrate_example_tables,
                  measure_feedrate_example_tables,
                  "studies/feedrate_example_tables.yaml",
                  [](const TablesOptions& o) {
                    return std::vector<std::filesystem::path>{
                        o.experiment_file("contour_error/feedrate.yaml")};
                  },
                  {"feedrate"}});
}

}  // namespace cnclab
