#pragma once
// Predictive feedrate optimisation with a contour-error constraint (seed
// 002's application: "the predictor was used in a predictive feedrate
// optimization algorithm with constrained contour error", abstract and
// conclusion): the fastest jerk-limited feedrate whose contour error, as the
// NARX contour predictor (contour_predictor.hpp) predicts it on the 1 ms
// reference, stays within a tolerance eps_max.
//
// Method: iterative local feed limits (docs/motion.md, "Feedrate with a
// contour-error constraint", says why this and not the predictor's
// sensitivities inside Ipopt):
//  1. plan the minimum-time feedrate under the axis limits (plan_feedrate);
//  2. interpolate its 1 ms reference and run the predictor over it from rest:
//     predicted |eps_c| per tick;
//  3. for every tick k with |eps_k| > s (eps_max - m) (s = safety_factor < 1,
//     m = prediction_margin, an allowance for the predictor's own error),
//     lower the path-speed cap (PathSpeedCap, a bound on the NLP's path
//     speed at grid nodes) at every cap knot within `margin` mm of arc length
//     of the tick to
//        v_k (s (eps_max - m) / |eps_k|)^(1 / error_exponent),
//     v_k the tick's path speed in this plan (so a cap only ever falls);
//  4. replan under the axis limits and the cap; repeat from 2 until the worst
//     predicted |eps| <= eps_max - m (converged) or max_iterations plans.
// With raise_caps, step 3 sets each knot to the smallest such speed over its
// window, also above the current cap, and the fastest plan within
// eps_max - m of all plans is the result.
// The knots of the cap are the unconstrained plan's grid nodes (about
// planner.grid_spacing apart), starting at the largest path speed the axis
// velocity limits allow (no effect).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "cnclab/motion/feedrate_planner.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "cnclab/studies/contour_error/contour_predictor.hpp"

namespace cnclab {

struct FeedrateOptimisationOptions {
  double tolerance = 0.005;  // eps_max [mm], > 0
  // s: caps aim at s eps_max, so the next plan lands under eps_max despite
  // the error's not quite following the assumed power law. In (0, 1].
  double safety_factor = 0.9;
  // m: what the predictor may under-predict the machine's contour error by
  // [mm]; the loop plans for a predicted error within eps_max - m. 0 trusts
  // the predictor. In [0, tolerance).
  double prediction_margin = 0.0;
  // p in |eps| ~ v^p near a tick: the cap scales by (s eps_max/|eps|)^(1/p).
  // The lag error of a P position loop grows like v (tangential) and the
  // centripetal part like v^2 (normal): 1 is cautious (more slowdown, fewer
  // plans), 2 optimistic. > 0.
  double error_exponent = 1.5;
  // Arc length on each side of an exceeding tick whose cap knots are
  // lowered [mm]: the error at a tick follows the reference of the last
  // few servo time constants (1/Kp = 25 ms at 40 1/s; 5 mm is 50 ms at
  // 100 mm/s). >= 0.
  double margin = 5.0;
  // Two-sided cap update (a fixed point rather than a descent): each plan
  // sets every cap knot anew to the smallest v_k (s (eps_max - m) / |eps_k|)^(1/p)
  // over the ticks within `margin` of it, so caps also rise where the
  // prediction is below the target (an early over-slowing is undone). The
  // loop then runs all max_iterations plans (or stops when no knot moves by
  // more than 1 %) and returns the fastest plan within eps_max - m. false:
  // caps only fall and the first plan within eps_max - m is returned.
  bool raise_caps = false;
  int max_iterations = 15;  // plans including the first, >= 1
  // A cap below this path speed [mm/s] means the tolerance cannot be met by
  // slowing down (the predictor's error at standstill, or its bias, exceeds
  // it): the optimisation stops with status infeasible. > 0.
  double min_speed = 1.0;
  FeedratePlannerOptions planner;  // axis limits, grid; its speed_cap is set by the loop

  void validate() const;  // OptionError naming the field
};

enum class OptimisationStatus { converged, max_iterations, infeasible };
const char* to_string(OptimisationStatus status) noexcept;

// One plan of the loop.
struct OptimisationIteration {
  double worst_predicted = 0.0;  // max predicted |eps| over the ticks [mm]
  double time = 0.0;             // traversal time [s]
  std::size_t ticks_over = 0;    // ticks with predicted |eps| > eps_max - m
  double min_cap = 0.0;          // smallest cap knot this plan was made with [mm/s]
  double seconds = 0.0;          // wall time of planning and prediction
};

struct FeedrateOptimisationResult {
  OptimisationStatus status = OptimisationStatus::max_iterations;
  std::string reason;  // why it stopped, in words
  FeedrateProfile profile;
  ReferenceTrajectory reference;               // interpolated at the predictor's 1 ms period
  std::vector<double> predicted;               // predicted |eps| per tick of `reference` [mm]
  PathSpeedCap cap;                            // the cap of the last plan
  std::vector<OptimisationIteration> history;  // [0] = the unconstrained plan
  double unconstrained_time() const { return history.empty() ? 0.0 : history.front().time; }
};

// Predicted |eps_c| per tick of `reference` (the predictor reset to rest
// first; ContourPredictor::step with the reference velocity and the path's
// C, C', C'' at the tick's u) [mm]. cnclab::Error naming the tick and the
// status when the predictor rejects a tick.
std::vector<double> predict_contour_error(ContourPredictor& predictor, const PlanarPath& path,
                                          const ReferenceTrajectory& reference);

// The loop's only view of the machine: |eps_c| per tick of a 1 ms reference
// [mm]. The NARX predictor (predict_contour_error) in the application; the
// simulated machine itself (check_on_machine's `simulated`) as a perfect
// predictor, which measures what the loop can reach apart from the
// predictor's error.
using ContourErrorModel = std::function<std::vector<double>(const ReferenceTrajectory&)>;

// The loop above. `progress` (optional) hears of each plan. Throws
// OptionError for bad options and what plan_feedrate throws; a tolerance
// that is not met is a result (status, reason), not an error.
FeedrateOptimisationResult optimise_feedrate(const PlanarPath& path,
                                             const ContourErrorModel& error_model,
                                             const FeedrateOptimisationOptions& options,
                                             const ProgressCallback& progress = {});
// The same with the NARX predictor (predict_contour_error) as the model.
FeedrateOptimisationResult optimise_feedrate(const PlanarPath& path, ContourPredictor& predictor,
                                             const FeedrateOptimisationOptions& options,
                                             const ProgressCallback& progress = {});

}  // namespace cnclab
