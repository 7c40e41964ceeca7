#pragma once
// A small sweep plan and trial outcomes shared by the summary and report tests.
#include <string>
#include <vector>

#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

namespace cnclab::sweep_fixtures {

// 3 points x 2 repeats over one key; metric "rmse".
inline SweepPlan plan_of(bool maximize) {
  SweepPlan plan;
  plan.experiment = std::string("e");  // (GCC 12 -Wrestrict false positive on = "...")
  plan.method = std::string("grid");
  plan.repeats = 2;
  plan.objective = {"rmse", maximize};
  plan.keys = {"trainer.learning_rate"};
  plan.metrics = {"rmse", "mae"};
  const char* values[] = {"0.1", "0.01", "0.001"};
  for (std::size_t p = 0; p < 3; ++p) {
    for (std::size_t r = 0; r < 2; ++r) {
      PlannedTrial t;
      t.point = p;
      t.repeat = r;
      t.seed = 42 + r;
      t.values = {values[p]};
      t.id = std::string(15, '0') + std::to_string(2 * p + r);
      plan.trials.push_back(t);
    }
  }
  return plan;
}

inline TrialOutcome complete(double rmse, double mae) {
  TrialOutcome o;
  o.status = TrialOutcome::Status::complete;
  o.metrics = {{"rmse", rmse}, {"mae", mae}};
  o.result_file = "trials/x.h5";
  return o;
}

inline TrialOutcome failed(const std::string& why) {
  TrialOutcome o;
  o.status = TrialOutcome::Status::failed;
  o.reason = why;
  return o;
}

inline std::vector<TrialOutcome> outcomes() {
  return {complete(2.0, 1.0), complete(4.0, 3.0),  // point 0: rmse mean 3, std sqrt(2)
          complete(1.0, 0.5), complete(1.5, 0.7),  // point 1: mean 1.25, std sqrt(0.125)
          failed("diverged"), TrialOutcome{}};     // point 2: failed + missing
}

}  // namespace cnclab::sweep_fixtures
