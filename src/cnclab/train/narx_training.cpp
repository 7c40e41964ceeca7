#include "cnclab/train/narx_training.hpp"

#include <algorithm>
#include <string>

#include "cnclab/core/error.hpp"

namespace cnclab {

std::vector<SequenceRange> sequence_ranges(Eigen::Index length,
                                           const std::vector<Eigen::Index>& starts,
                                           Eigen::Index min_length) {
  std::vector<SequenceRange> out;
  Eigen::Index begin = 0;
  for (std::size_t i = 0; i <= starts.size(); ++i) {
    const Eigen::Index end = i < starts.size() ? starts[i] : length;
    if (!(end > begin && end <= length)) {
      throw Error("NARX sequences: start " + std::to_string(end) + " is not after " +
                  std::to_string(begin) + " within the series of " + std::to_string(length) +
                  " samples");
    }
    if (end - begin <= min_length) {
      throw Error("NARX sequences: sequence " + std::to_string(i) + " [" + std::to_string(begin) +
                  ", " + std::to_string(end) + ") has " + std::to_string(end - begin) +
                  " samples; need > " + std::to_string(min_length) + " (the delays)");
    }
    out.push_back({begin, end});
    begin = end;
  }
  return out;
}

namespace {

// The open-loop regressors of every sequence, side by side.
Eigen::MatrixXd sequences_regressors(const Narx& narx, const Narx::Inputs& v,
                                     const Eigen::VectorXd& e,
                                     const std::vector<Eigen::Index>& starts) {
  if (starts.empty()) return narx.open_loop_regressors(v, e);
  const auto seqs = sequence_ranges(e.size(), starts, narx.first_step());
  Eigen::MatrixXd x(narx.num_inputs(),
                    e.size() - narx.first_step() * static_cast<Eigen::Index>(seqs.size()));
  Eigen::Index col = 0;
  for (const auto& q : seqs) {
    const Eigen::Index n = q.end - q.begin;
    x.middleCols(col, n - narx.first_step()) =
        narx.open_loop_regressors(v.middleRows(q.begin, n), e.segment(q.begin, n));
    col += n - narx.first_step();
  }
  return x;
}

// The measured e at the predicted steps of every sequence, as one row.
Eigen::MatrixXd sequences_targets(const Narx& narx, const Eigen::VectorXd& e,
                                  const std::vector<Eigen::Index>& starts) {
  const auto seqs = sequence_ranges(e.size(), starts, narx.first_step());
  Eigen::MatrixXd y(1, e.size() - narx.first_step() * static_cast<Eigen::Index>(seqs.size()));
  Eigen::Index col = 0;
  for (const auto& q : seqs) {
    const Eigen::Index n = q.end - q.begin - narx.first_step();
    y.row(0).segment(col, n) = e.segment(q.begin + narx.first_step(), n).transpose();
    col += n;
  }
  return y;
}

}  // namespace

NarxOpenLoopObjective::NarxOpenLoopObjective(const Narx& narx, const Narx::Inputs& v,
                                             const Eigen::VectorXd& e,
                                             const std::vector<Eigen::Index>& starts)
    : inputs_(sequences_regressors(narx, v, e, starts)),
      targets_(sequences_targets(narx, e, starts)),
      static_(narx.mlp(), inputs_, targets_) {}

NarxClosedLoopObjective::NarxClosedLoopObjective(const Narx& narx, const Narx::Inputs& v,
                                                 const Eigen::VectorXd& e, Eigen::Index horizon,
                                                 const std::vector<Eigen::Index>& starts)
    : narx_(narx), v_(v), e_(e), horizon_(horizon) {
  narx.open_loop_regressors(v, e);  // the same checks on the series (lengths, NaN)
  if (horizon < 0) throw Error("closed-loop horizon " + std::to_string(horizon) + " < 0");
  sequences_ = sequence_ranges(e.size(), starts, narx.first_step());
  for (const auto& q : sequences_) residual_count_ += q.end - q.begin - narx.first_step();
}

void NarxClosedLoopObjective::evaluate(const Eigen::VectorXd& params, Eigen::Index first,
                                       Eigen::Index count, Eigen::Ref<Eigen::VectorXd> residuals,
                                       Eigen::MatrixXd* jacobian) {
  const bool same = cached_params_.size() == params.size() && cached_params_ == params;
  if (!same || (jacobian != nullptr && !has_jacobian_)) {
    has_jacobian_ = jacobian != nullptr;
    simulate(params);
    cached_params_ = params;
  }
  residuals = residuals_.segment(first, count);
  if (jacobian != nullptr) *jacobian = jacobian_.middleRows(first, count);
}

void NarxClosedLoopObjective::simulate(const Eigen::VectorXd& params) {
  const Eigen::Index steps = num_residuals(), t0 = narx_.first_step();
  if (sequences_.size() == 1 && (horizon_ == 0 || horizon_ >= steps)) {
    // One window: no copies of the series or the Jacobian.
    residuals_ = narx_.simulate_closed_loop(params, v_, e_, has_jacobian_ ? &jacobian_ : nullptr) -
                 e_.tail(steps);
    return;
  }
  residuals_.resize(steps);
  if (has_jacobian_) jacobian_.resize(steps, num_parameters());
  Eigen::MatrixXd window_jacobian;
  Eigen::Index row = 0;  // the residual row of the window's first prediction
  for (const auto& q : sequences_) {
    const Eigen::Index seq_steps = q.end - q.begin - t0;
    const Eigen::Index window = horizon_ > 0 ? std::min(horizon_, seq_steps) : seq_steps;
    // Window [s, s + n) of the sequence's steps predicts its samples
    // t0 + s .. t0 + s + n - 1 from the measured states e(s .. s + t0 - 1)
    // and the inputs from s on.
    for (Eigen::Index s = 0; s < seq_steps; s += window) {
      const Eigen::Index n = std::min(window, seq_steps - s);
      const Eigen::Index first = q.begin + s;
      const Eigen::VectorXd e = e_.segment(first, t0 + n);
      residuals_.segment(row, n) =
          narx_.simulate_closed_loop(params, v_.middleRows(first, t0 + n), e,
                                     has_jacobian_ ? &window_jacobian : nullptr) -
          e.tail(n);
      if (has_jacobian_) jacobian_.middleRows(row, n) = window_jacobian;
      row += n;
    }
  }
}

void NarxTrainingOptions::validate() const {
  const auto prefixed = [](const char* stage, const TrainbrOptions& o) {
    try {
      o.validate();
    } catch (const OptionError& e) {
      throw OptionError(std::string(stage) + "." + e.field(), e.value(), e.rule());
    }
  };
  prefixed("open_loop", open_loop);
  prefixed("closed_loop", closed_loop);
  if (!run_open_loop && !run_closed_loop) {
    throw OptionError("run_open_loop, run_closed_loop", "false, false", "run at least one stage");
  }
}

NarxTrainingResult train_narx(const Narx& narx, const Narx::Inputs& v, const Eigen::VectorXd& e,
                              Eigen::VectorXd& params, const NarxTrainingOptions& options) {
  options.validate();
  if (params.size() != static_cast<Eigen::Index>(narx.num_parameters())) {
    throw Error("train_narx: " + std::to_string(params.size()) + " parameters, the network has " +
                std::to_string(narx.num_parameters()));
  }
  NarxTrainingResult result;
  if (options.run_open_loop) {
    NarxOpenLoopObjective open(narx, v, e);
    result.open_loop = train_trainbr(open, params, options.open_loop);
  }
  if (options.run_closed_loop) {
    NarxClosedLoopObjective closed(narx, v, e);
    result.closed_loop = train_trainbr(closed, params, options.closed_loop);
  }
  return result;
}

}  // namespace cnclab
