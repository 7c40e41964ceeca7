#pragma once
// The feedrate problem of one window as an Ipopt TNLP (internal to the
// feedrate planner; see feedrate_planner.hpp for the formulation).
//
// Scaled units: time T0 = A/J, length L0 = A T0^2 (A, J the smallest axis
// acceleration and jerk limits), so the optimal variables are O(1). The path
// coordinate is w = (u - u_begin) * lambda / L0, lambda the mean parametric
// speed |C'| in mm per unit u, so w is roughly arc length / L0.
//
// Variables: node k = 0..N: v_k = dw/dt, a_k = d2w/dt2; interval k = 0..N-1:
// duration h_k > 0 and constant path jerk j_k = d3w/dt3, so w(t) is a cubic
// on each interval and the discrete profile is an exact motion. Layout:
// x[4k] = v_k, x[4k+1] = a_k, x[4k+2] = h_k, x[4k+3] = j_k.
//
// Objective: sum h_k (traversal time). Constraints per interval (exact
// kinematics of constant jerk):
//   v_k h + a_k h^2/2 + j_k h^3/6 = w_k+1 - w_k,
//   v_k+1 = v_k + a_k h + j_k h^2/2,   a_k+1 = a_k + j_k h;
// per node and axis i (ratios to the limits, in [-1, 1]):
//   velocity      q1_i v                               (a bound on v_k,
//                 also capped by v_cap, the path-speed cap, if any)
//   acceleration  q2_i v^2 + q1_i a                    (interior nodes)
//   jerk          q3_i v^3 + 3 q2_i v a + q1_i j       (both ends of every interval)
// where q1, q2, q3 are dq/dw, d2q/dw2, d3q/dw3 divided by the limit and the
// matching power of T0.
#include <IpTNLP.hpp>
#include <array>
#include <vector>

namespace cnclab::feedrate_detail {

// Geometry of one node, already divided by the limits (see above).
struct NodeCoefficients {
  std::array<double, 2> vel{};                      // q1_i / (V_i T0)
  std::array<double, 2> acc1{}, acc2{};             // q1_i, q2_i / (A_i T0^2)
  std::array<double, 2> jerk1{}, jerk2{}, jerk3{};  // q1_i, q2_i, q3_i / (J_i T0^3)
  double w = 0.0;                                   // path coordinate
  // Upper bound on v from a path-speed cap (PathSpeedCap): speed = |q1| v / T0
  // [mm/s] with q1 = dq/dw, so v <= cap T0 / |q1|. 1e19 (Ipopt's "none"): no cap.
  double v_cap = 1e19;
};

struct WindowState {
  double v = 0.0, a = 0.0;
};

class FeedrateNlp final : public Ipopt::TNLP {
 public:
  // `guess` holds 4N+2 values in the layout above. The window starts in
  // state `start` and ends in state `end` (rest for the planner's windows; the
  // current plan's state there for the limit refinement's local windows).
  FeedrateNlp(std::vector<NodeCoefficients> nodes, WindowState start, std::vector<double> guess,
              WindowState end = {});

  const std::vector<double>& solution() const { return solution_; }

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g,
                    Ipopt::Index& nnz_h_lag, IndexStyleEnum& index_style) override;
  bool get_bounds_info(Ipopt::Index n, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index m,
                       Ipopt::Number* g_l, Ipopt::Number* g_u) override;
  bool get_starting_point(Ipopt::Index n, bool init_x, Ipopt::Number* x, bool init_z,
                          Ipopt::Number* z_L, Ipopt::Number* z_U, Ipopt::Index m, bool init_lambda,
                          Ipopt::Number* lambda) override;
  bool eval_f(Ipopt::Index n, const Ipopt::Number* x, bool new_x,
              Ipopt::Number& obj_value) override;
  bool eval_grad_f(Ipopt::Index n, const Ipopt::Number* x, bool new_x,
                   Ipopt::Number* grad_f) override;
  bool eval_g(Ipopt::Index n, const Ipopt::Number* x, bool new_x, Ipopt::Index m,
              Ipopt::Number* g) override;
  bool eval_jac_g(Ipopt::Index n, const Ipopt::Number* x, bool new_x, Ipopt::Index m,
                  Ipopt::Index nele_jac, Ipopt::Index* iRow, Ipopt::Index* jCol,
                  Ipopt::Number* values) override;
  bool eval_h(Ipopt::Index n, const Ipopt::Number* x, bool new_x, Ipopt::Number obj_factor,
              Ipopt::Index m, const Ipopt::Number* lambda, bool new_lambda, Ipopt::Index nele_hess,
              Ipopt::Index* iRow, Ipopt::Index* jCol, Ipopt::Number* values) override;
  void finalize_solution(Ipopt::SolverReturn status, Ipopt::Index n, const Ipopt::Number* x,
                         const Ipopt::Number* z_L, const Ipopt::Number* z_U, Ipopt::Index m,
                         const Ipopt::Number* g, const Ipopt::Number* lambda,
                         Ipopt::Number obj_value, const Ipopt::IpoptData* ip_data,
                         Ipopt::IpoptCalculatedQuantities* ip_cq) override;

 private:
  int intervals() const { return static_cast<int>(nodes_.size()) - 1; }
  // Rows: 3 kinematic equalities per interval, then 2 acceleration rows per
  // interior node, then 4 jerk rows per interval (axis x/y at left/right end).
  int acc_row(int node, int axis) const { return 3 * intervals() + 2 * (node - 1) + axis; }
  int jerk_row(int interval, int end, int axis) const {
    return 3 * intervals() + 2 * (intervals() - 1) + 4 * interval + 2 * end + axis;
  }

  std::vector<NodeCoefficients> nodes_;
  WindowState start_;
  std::vector<double> guess_;
  WindowState end_;
  std::vector<double> solution_;
};

}  // namespace cnclab::feedrate_detail
