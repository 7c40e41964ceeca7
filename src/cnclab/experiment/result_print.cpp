// `cnclab show` of a training result: the model, how validation was used,
// provenance, metrics, config (declared in result_file.hpp).
#include <algorithm>
#include <string>
#include <vector>

#include "cnclab/core/config_abbreviate.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/result_inference.hpp"
#include "cnclab/experiment/run_warnings.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/train/trainer_registry.hpp"

namespace cnclab {

namespace {
// The model and training lines of a narx run.
void print_narx_model(const RunRecord& r, std::ostream& out) {
  const NarxRecord& n = *r.narx;
  const NarxOptions& o = n.options;
  out << "model        narx, one network per target: " << o.hidden << " "
      << to_string(o.hidden_activation) << " units, input delays " << o.first_input_delay << ".."
      << o.first_input_delay + o.input_delays - 1 << ", feedback delays 1.." << o.feedback_delays;
  if (!n.networks.empty()) out << " (" << n.networks[0].parameters.size() << " parameters each)";
  out << "\n";
  out << "training     " << r.trainer << ", " << to_string(r.training.termination) << "\n";
  for (const auto& net : n.networks) {
    out << "  " << net.axis << " (" << join(net.inputs, ", ") << " -> " << net.target << ", "
        << format_metric(net.seconds) << " s):";
    for (const auto& st : net.stages) {
      out << (st.fallback ? " second try: " : " ") << st.mode;
      if (st.horizon != 0) out << " (windows of " << st.horizon << " steps)";
      out << " " << st.trainer << " " << st.summary.history.size() << " epochs ("
          << to_string(st.summary.termination) << ")";
      const Summary& sm = st.summary;
      if (sm.lm_initial) out << " SSE " << format_metric(sm.lm_initial->sse) << " ->";
      if (!sm.lm_history.empty()) {
        out << (sm.lm_initial ? " " : " SSE ") << format_metric(sm.lm_history.back().sse);
      } else if (sm.lm_initial) {
        out << " (no step)";
      }
      out << ";";
    }
    out << "\n";
  }
}

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

void print_metrics(const RunRecord& r, const std::string& note, std::ostream& out) {
  std::size_t name_width = 14, value_width = 0;
  for (const auto& [name, value] : r.metrics) {
    name_width = std::max(name_width, name.size() + 2);
    value_width = std::max(value_width, format_metric(value).size() + 2);
  }
  out << "metrics" << (note.empty() ? "" : "      (" + note + ")") << "\n";
  // Split by split (train, validation, test), then names without a split.
  std::vector<std::pair<std::string, double>> ordered(r.metrics.begin(), r.metrics.end());
  const auto rank = [](const std::string& name) {
    const auto& splits = metric_splits();
    return std::find(splits.begin(), splits.end(), metric_split(name)) - splits.begin();
  };
  std::stable_sort(ordered.begin(), ordered.end(),
                   [&](const auto& a, const auto& b) { return rank(a.first) < rank(b.first); });
  for (const auto& [name, value] : ordered) {
    const auto it = r.metric_units.find(name);
    const std::string unit = it == r.metric_units.end() ? "" : it->second;
    std::string line = "  " + name + std::string(name_width - name.size(), ' ') +
                       format_metric(value) +
                       std::string(value_width - format_metric(value).size(), ' ') +
                       (unit == "1" ? "1 (dimensionless)" : unit);
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out << line << "\n";
  }
}

void print_result_config(const std::string& resolved_yaml, std::ostream& out,
                         const ShowOptions& options) {
  const AbbreviatedConfig shown =
      options.full_config ? AbbreviatedConfig{resolved_yaml, 0} : abbreviate_config(resolved_yaml);
  out << "config";
  if (shown.abbreviated > 0) {
    out << " (" << shown.abbreviated << " array(s) of more than " << kAbbreviateScalars
        << " numbers abbreviated; --full prints them)";
  }
  out << "\n";
  const std::string& text = shown.text;
  std::size_t start = 0;
  while (start < text.size()) {
    const auto end = text.find('\n', start);
    out << "  " << text.substr(start, end - start) << "\n";
    if (end == std::string::npos) break;
    start = end + 1;
  }
}

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
