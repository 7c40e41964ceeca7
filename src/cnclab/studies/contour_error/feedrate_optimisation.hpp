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
//  3. for every tick k with |eps_k| > s (eps_max - m_k) (s = safety_factor < 1,
//     m_k = prediction_margin, or the tick's margin_bands entry: an allowance
//     for the predictor's own error),
//     lower the path-speed cap (PathSpeedCap, a bound on the NLP's path
//     speed at grid nodes) at every cap knot within `margin` mm of arc length
//     of the tick to
//        v_k (s (eps_max - m_k) / |eps_k|)^(1 / error_exponent),
//     v_k the tick's path speed in this plan (so a cap only ever falls);
//  4. replan under the axis limits and the cap; repeat from 2 until
//     |eps_k| <= eps_max - m_k at every tick (converged; ticks slower than
//     standstill_speed excepted) or max_iterations plans.
// With raise_caps, step 3 sets each knot to the smallest such speed over its
// window, also above the current cap, and the fastest plan within
// eps_max - m_k of all plans is the result.
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

// A prediction margin per feed band [mm]: margin[b] applies to a tick whose
// path speed |v| lies in band b = [edges[b-1], edges[b]) (edges[-1] = 0,
// edges[size] = infinity). Empty: no bands. With a reversal window, a tick
// at most reversal_window after either axis's commanded direction last
// changed (AxisDirection::since_change: a reversal, or the start from rest)
// takes after_reversal[b] instead: the stick-slip transient there is what
// the predictor misses most (docs/motion.md, "Calibrated
// margins").
struct FeedBandMargins {
  std::vector<double> edges;                // ascending, > 0 [mm/s]
  std::vector<double> margin;               // edges.size() + 1 values [mm], >= 0
  double reversal_window = 0.0;             // [s], >= 0; 0: no reversal class
  std::vector<double> after_reversal = {};  // empty, or as margin when reversal_window > 0 [mm]
  bool empty() const noexcept { return margin.empty(); }
  std::size_t band(double speed) const noexcept;
  // Whether a tick since_change [s] after the last change of direction of
  // either axis is in the window (a tick at its end counts: 1 ns slack for
  // the rounding of ticks * period).
  bool after_reversal_at(double since_change) const noexcept {
    return reversal_window > 0.0 && since_change <= reversal_window + 1e-9;
  }
  // The margin of a tick at path speed |v| [mm/s], since_change [s] after
  // the last change of direction of either axis.
  double at(double speed, double since_change) const noexcept;
  void validate() const;  // OptionError naming the field
};

struct FeedrateOptimisationOptions {
  double tolerance = 0.005;  // eps_max [mm], > 0
  // s: caps aim at s eps_max, so the next plan lands under eps_max despite
  // the error's not quite following the assumed power law. In (0, 1].
  double safety_factor = 0.9;
  // m: what the predictor may under-predict the machine's contour error by
  // [mm]; the loop plans for a predicted error within eps_max - m. 0 trusts
  // the predictor. In [0, tolerance).
  double prediction_margin = 0.0;
  // Instead of prediction_margin when not empty: m per feed band of the
  // tick (margin_calibration.hpp calibrates it on held-out plans). A band
  // whose margin reaches eps_max leaves nothing to plan for at that feed:
  // the loop slows down out of it, or ends infeasible.
  FeedBandMargins margin_bands;
  // The margin of every tick of a reference [mm] (its axis velocities give
  // the path speed and the time since a change of direction).
  std::vector<double> tick_margins(const ReferenceTrajectory& reference) const;
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
  // Also the unconstrained plan slowed by one factor f (time_scaled, u(f t))
  // with f the largest the error model keeps within eps_max - m (bisection,
  // `uniform_steps` steps over [min_factor, 1]); the faster of it and the
  // local-limit plan is the result. Local limits should never lose to one
  // feed override judged by the same model (where the error is spread
  // evenly one factor is near optimal, and the loop's safety factor and
  // caps that only fall slow it down more than needed).
  bool uniform_candidate = false;
  int uniform_steps = 12;    // >= 1
  double min_factor = 0.02;  // in (0, 1)
  int max_iterations = 15;   // plans including the first, >= 1
  // A cap below this path speed [mm/s] means the tolerance cannot be met by
  // slowing down (the predictor's error at standstill, or its bias, exceeds
  // it): the optimisation stops with status infeasible. > 0.
  double min_speed = 1.0;
  // Ticks of a plan slower than this path speed [mm/s] are not held to the
  // bound (0: every tick is). A plan from rest starts and ends with the same
  // few jerk-limited ticks under any cap or factor, so the loop cannot
  // change their error: a predictor's start-up transient there makes every
  // plan infeasible (measured on the any-path study: 12 um predicted 3 ms
  // after a cold start, at 0.23 mm/s, where the machine has 2.6 um). The
  // verification on the machine still judges every tick. In [0, min_speed].
  double standstill_speed = 0.0;
  bool at_standstill(double speed) const noexcept { return speed < standstill_speed; }
  FeedratePlannerOptions planner;  // axis limits, grid; its speed_cap is set by the loop

  void validate() const;  // OptionError naming the field
};

enum class OptimisationStatus { converged, max_iterations, infeasible };
const char* to_string(OptimisationStatus status) noexcept;

// One plan of the loop.
struct OptimisationIteration {
  double worst_predicted = 0.0;  // max predicted |eps| over the ticks [mm]
  // max over the ticks of predicted |eps| + m(|v|) - eps_max [mm]: <= 0 within
  double worst_excess = 0.0;
  double time = 0.0;           // traversal time [s]
  std::size_t ticks_over = 0;  // ticks with predicted |eps| > eps_max - m
  double min_cap = 0.0;        // smallest cap knot this plan was made with [mm/s]
  double seconds = 0.0;        // wall time of planning and prediction
};

struct FeedrateOptimisationResult {
  OptimisationStatus status = OptimisationStatus::max_iterations;
  std::string reason;  // why it stopped, in words
  FeedrateProfile profile;
  ReferenceTrajectory reference;               // interpolated at the predictor's 1 ms period
  std::vector<double> predicted;               // predicted |eps| per tick of `reference` [mm]
  PathSpeedCap cap;                            // the cap of the last plan
  std::vector<OptimisationIteration> history;  // [0] = the unconstrained plan
  // uniform_candidate: the factor the model allowed (0: none met the bound),
  // and whether that plan is the result.
  double uniform_factor = 0.0;
  bool uniform_chosen = false;
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
