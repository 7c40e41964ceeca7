// `cnclab show` of a training result: the model, how validation was used,
// provenance, metrics, config (declared in result_file.hpp).
#include <string>
#include <vector>

#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/result_inference.hpp"
#include "cnclab/experiment/result_narx.hpp"
#include "cnclab/experiment/run_warnings.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/train/trainer_registry.hpp"

namespace cnclab {

namespace {
void print_mlp_model(const RunRecord& r, std::ostream& out) {
  out << "model        mlp " << r.model.inputs;
  for (auto h : r.model.hidden) out << "-" << h;
  out << "-" << r.model.outputs << " (" << to_string(r.model.hidden_activation) << ", keep p "
      << format_metric(r.model.dropout_keep_probability) << ", " << r.parameters.size()
      << " parameters)\n";
  out << "training     " << r.trainer << ", " << to_string(r.training.termination) << ": "
      << r.training.message << "\n";
  if (!r.training.history.empty()) {
    const auto& last = r.training.history.back();
    out << "             final train loss " << format_metric(last.train_loss);
    if (!r.test_loss.empty()) out << ", test loss " << format_metric(r.test_loss.back());
    out << " (normalised MSE) after " << last.epoch << " epochs, "
        << format_metric(last.wall_seconds) << " s\n";
  }
  if (!r.training.lm_history.empty()) {
    const auto& lm = r.training.lm_history.back();
    out << "             final SSE " << format_metric(lm.sse) << ", SSW " << format_metric(lm.ssw)
        << ", mu " << format_metric(lm.mu) << ", gradient " << format_metric(lm.gradient) << "\n";
    const TrainerDef* trainer = trainers().find(r.trainer);
    if (trainer && trainer->history == TrainerHistory::bayesian) {
      out << "             alpha " << format_metric(lm.alpha) << ", beta " << format_metric(lm.beta)
          << ", gamma " << format_metric(lm.gamma) << " of " << r.parameters.size()
          << " parameters effective";
      if (r.training.beta_guard_count > 0) {
        out << "; beta guard (N - gamma <= 0, previous beta kept) in "
            << r.training.beta_guard_count << " epochs";
      }
      out << "\n";
    }
  }
}

}  // namespace

std::vector<std::string> validation_notes(const RunRecord& r) {
  const std::string held_out =
      r.split.validation.empty()
          ? ""
          : ": the " + std::to_string(r.split.validation.size()) +
                (r.narx ? " steps of the validation half" : " validation samples") +
                " are held out of training and only scored (validation.*)";
  if (r.narx) {
    // The first stage trainer without a validation stop, named with its reason.
    std::string without;
    for (const auto& net : r.narx->networks) {
      for (const auto& st : net.stages) {
        const TrainerDef* t = trainers().find(st.trainer);
        if (without.empty() && t && !t->capabilities.validation_stop) {
          without = " (" + t->name + " has no validation stop, " + t->without_validation_stop + ")";
        }
      }
    }
    return {"no training stage stops on the validation half" + without + held_out};
  }
  const TrainerDef* trainer = trainers().find(r.trainer);
  if (trainer && !trainer->capabilities.validation_stop) {
    return {trainer->name + " has no validation stop (" + trainer->without_validation_stop + ")" +
            held_out};
  }
  return {};
}

void print_provenance(const Provenance& p, std::ostream& out) {
  for (const auto& [label, text] : provenance_lines(p)) {
    out << label << std::string(label.size() < 13 ? 13 - label.size() : 1, ' ') << text << "\n";
  }
}

void print_result(const RunRecord& r, std::ostream& out, const ShowOptions& options) {
  if (r.kind != "train") {
    print_job_result(r, out, options);
    return;
  }
  const Provenance& p = r.provenance;
  out << "experiment   " << r.experiment << "\n"
      << "status       " << status_text(p.status, r.warnings)
      << (p.failure_reason.empty() ? "" : ": " + p.failure_reason) << "\n";
  print_provenance(p, out);
  out << "seed         " << p.master_seed << " (";
  bool first = true;
  for (const auto& [name, seed] : p.derived_seeds) {
    out << (first ? "" : ", ") << name << " " << seed;
    first = false;
  }
  out << ")\n";
  out << "dataset      " << r.dataset_file << " ("
      << r.test_targets.cols() +
             static_cast<Eigen::Index>(r.split.train.size() + r.split.validation.size())
      << " samples, hash " << r.dataset_hash << ")\n"
      << "split        train " << r.split.train.size() << ", validation "
      << r.split.validation.size() << ", test " << r.split.test.size() << "\n";
  if (r.narx) {
    print_narx_model(r, out);
  } else {
    print_mlp_model(r, out);
  }
  for (const auto& note : validation_notes(r)) out << "validation   " << note << "\n";
  bool normalised = false;
  for (const auto& [name, value] : r.metrics)
    normalised = normalised || metric_base(name).starts_with("normalised_");
  std::string note =
      r.narx ? "validation half, closed loop; no test split (sequential halves)" : "per split";
  if (r.format_version < 2 && !r.narx) {
    note += "; an older result (format 1): the test split and validation.normalised_mse only";
  }
  if (normalised) note += "; scaled²: the network's scaled target units";
  print_metrics(r, note, out);
  print_inference(r, out);
  print_result_config(r.resolved_yaml, out, options);
}

}  // namespace cnclab
