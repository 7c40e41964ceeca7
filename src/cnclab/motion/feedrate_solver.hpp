#pragma once
// Internal to the feedrate planner: the scaled units of the NLP
// (feedrate_nlp.hpp), the per-node coefficients, one Ipopt application that
// solves window after window, and the map from the whole path's scaled
// solution back to a FeedrateProfile.
#include <IpIpoptApplication.hpp>
#include <string>
#include <vector>

#include "cnclab/motion/feedrate_nlp.hpp"
#include "cnclab/motion/feedrate_planner.hpp"

namespace cnclab::feedrate_detail {

// Scaled units: T0 = A/J [s], L0 = A T0^2 [mm] (A, J the smallest axis
// limits), and the map u -> w = (u - u_begin) * lambda / L0, lambda the mean
// |C'| in mm per unit u.
struct Scaling {
  double T0 = 1.0, L0 = 1.0, lambda = 1.0, u_begin = 0.0;
  double du_dw() const { return L0 / lambda; }
  static Scaling for_path(const PlanarPath& path, const PlanarLimits& limits);
};

// Coefficients of the node at parameter u, path derivatives `p` there;
// `speed_cap` [mm/s] the path-speed cap there (infinity: none).
NodeCoefficients node_coefficients(const PathPoint& p, double u, const Scaling& s,
                                   const PlanarLimits& limits, double speed_cap);

// A plan in scaled units over the whole path: grid nodes (parameter u), their
// coefficients, and the solution in the NLP layout (x[4k] = v_k,
// x[4k+1] = a_k, x[4k+2] = h_k, x[4k+3] = j_k; 4N + 2 values).
struct ScaledPlan {
  std::vector<double> grid;
  std::vector<NodeCoefficients> nodes;
  std::vector<double> x;
};

// Back to physical units: u = u_begin + w du/dw, t = T0 t~ (windows and
// refinement summary left empty).
FeedrateProfile to_profile(const ScaledPlan& plan, const Scaling& s);

struct WindowSolution {
  std::vector<double> x;  // NLP layout, 4N + 2 values
  int iterations = -1;    // Ipopt iterations (-1: unknown)
  double seconds = 0.0;   // wall time of the solve
};

class WindowSolver {
 public:
  // Ipopt options from the planner's tolerance and max_iterations; throws
  // cnclab::Error if Ipopt fails to initialise.
  explicit WindowSolver(const FeedratePlannerOptions& options);
  // Solves one window from `start` to `end`. Anything but Solve_Succeeded or
  // Solved_To_Acceptable_Level throws cnclab::Error "feedrate planning failed
  // in <where>: Ipopt returned <status> (<code>)".
  WindowSolution solve(std::vector<NodeCoefficients> nodes, WindowState start,
                       std::vector<double> guess, WindowState end, const std::string& where);

 private:
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app_;
};

}  // namespace cnclab::feedrate_detail
