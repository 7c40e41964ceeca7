#pragma once
// Training a NARX network (nn/narx.hpp) the two-stage way of seed 002
// (Sec. II): (1) series-parallel (open loop: the measured errors are fed
// back, the network is a static MLP on the regressors) with trainbr from
// random weights; (2) the loop closed, trainbr continued in the parallel
// configuration from the same weights, with the exact dynamic Jacobian of
// the closed-loop outputs (RTRL, Narx::simulate_closed_loop).
// Residuals are prediction minus measurement at steps t = first_step()..T-1.
//
// A series may hold several independent sequences (e.g. one run of a path
// per feed factor): `starts` lists the first sample of every sequence after
// the first (ascending, each sequence longer than first_step()). Each
// sequence is then a series of its own: no regressor and no prediction
// reaches across a start, and each is predicted from its own measured
// initial states, as a series split in two (seed 002's halves) is.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "cnclab/nn/narx.hpp"
#include "cnclab/train/mlp_residuals.hpp"
#include "cnclab/train/residual_objective.hpp"
#include "cnclab/train/summary.hpp"
#include "cnclab/train/trainbr.hpp"

namespace cnclab {

// The sequences of a series of `length` samples: [begin, end) each, from
// `starts` (see above). cnclab::Error naming the sequence when one is not
// longer than `min_length` or `starts` is not ascending within (0, length).
struct SequenceRange {
  Eigen::Index begin = 0, end = 0;
};
std::vector<SequenceRange> sequence_ranges(Eigen::Index length,
                                           const std::vector<Eigen::Index>& starts,
                                           Eigen::Index min_length);

// Series-parallel residuals: the static network on the open-loop regressors
// (MlpResidualObjective, Jacobian by Mlp::output_jacobian), of every sequence.
class NarxOpenLoopObjective : public ResidualObjective {
 public:
  NarxOpenLoopObjective(const Narx& narx, const Narx::Inputs& v, const Eigen::VectorXd& e,
                        const std::vector<Eigen::Index>& starts = {});
  Eigen::Index num_residuals() const override { return static_.num_residuals(); }
  Eigen::Index num_parameters() const override { return static_.num_parameters(); }
  void evaluate(const Eigen::VectorXd& params, Eigen::Index first, Eigen::Index count,
                Eigen::Ref<Eigen::VectorXd> residuals, Eigen::MatrixXd* jacobian) override {
    static_.evaluate(params, first, count, residuals, jacobian);
  }

 private:
  Eigen::MatrixXd inputs_, targets_;
  MlpResidualObjective static_;
};

// Parallel residuals e_hat(t) - e(t), e_hat from the closed-loop simulation
// started from the measured initial states (of each sequence). The
// simulation is sequential: one pass (with the dynamic Jacobian when asked)
// per parameter vector, cached and served in row blocks.
//
// horizon H > 0: the steps are predicted in consecutive windows of H steps
// (the last one shorter), each started afresh from the measured states
// before it, so a prediction depends on the weights only through at most
// H - 1 fed-back predictions. The residuals are the same steps as with one
// window (H = 0): every step after the first D is predicted once. Why:
// docs/narx_training.md (the RTRL sensitivities of an unstable closed loop
// grow along the whole series; short windows bound them).
class NarxClosedLoopObjective : public ResidualObjective {
 public:
  // v and e are copied (the objective outlives no caller's series).
  NarxClosedLoopObjective(const Narx& narx, const Narx::Inputs& v, const Eigen::VectorXd& e,
                          Eigen::Index horizon = 0, const std::vector<Eigen::Index>& starts = {});
  Eigen::Index num_residuals() const override { return residual_count_; }
  Eigen::Index num_parameters() const override {
    return static_cast<Eigen::Index>(narx_.num_parameters());
  }
  void evaluate(const Eigen::VectorXd& params, Eigen::Index first, Eigen::Index count,
                Eigen::Ref<Eigen::VectorXd> residuals, Eigen::MatrixXd* jacobian) override;

 private:
  const Narx& narx_;
  Eigen::MatrixXd v_;
  Eigen::VectorXd e_;
  Eigen::Index horizon_;  // steps per window; the whole sequence when 0
  std::vector<SequenceRange> sequences_;
  Eigen::Index residual_count_ = 0;  // sum over the sequences of their length - first_step
  Eigen::VectorXd cached_params_, residuals_;
  Eigen::MatrixXd jacobian_;
  bool has_jacobian_ = false;

  void simulate(const Eigen::VectorXd& params);  // residuals_ (and jacobian_) at params
};

// trainbr with seed 002's stopping rule: "until minimum gradient of 1e-8
// was reached or the training did not show significant progress" (the
// latter: mu exceeding mu_max, or the epoch limit).
inline TrainbrOptions seed002_trainbr() {
  TrainbrOptions o;
  o.min_gradient = 1e-8;
  return o;
}

struct NarxTrainingOptions {
  TrainbrOptions open_loop = seed002_trainbr();    // stage 1, series-parallel, random weights
  TrainbrOptions closed_loop = seed002_trainbr();  // stage 2, parallel, from stage 1's weights
  bool run_open_loop = true;    // false: closed-loop only (from the given weights)
  bool run_closed_loop = true;  // false: open-loop only

  void validate() const;  // both stages' options; at least one stage
};

struct NarxTrainingResult {
  std::optional<Summary> open_loop, closed_loop;  // present for the stages run
};

// Trains `params` in place (initialise it first: Narx::initialise).
NarxTrainingResult train_narx(const Narx& narx, const Narx::Inputs& v, const Eigen::VectorXd& e,
                              Eigen::VectorXd& params, const NarxTrainingOptions& options = {});

}  // namespace cnclab
