#include "cnclab/report/sweep_report.hpp"

#include <cmath>
#include <string>

#include "cnclab/nn/metrics.hpp"
#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

std::string mean_std_text(const PointStats& p, const std::string& metric) {
  const double mean = metric_or_nan(p.mean, metric);
  if (std::isnan(mean)) return "—";
  const double sd = metric_or_nan(p.std, metric);
  return format_metric(mean) + (std::isnan(sd) ? "" : " ± " + format_metric(sd));
}

// "2/2", or "2/2, 1 warning" when complete trials of the point carry warnings
// (listed below the table).
std::string ok_runs_text(const PointStats& p, const std::vector<TrialOutcome>& outcomes) {
  std::size_t warned = 0;
  for (std::size_t i : p.trials) warned += outcomes[i].warnings.empty() ? 0 : 1;
  std::string s = std::to_string(p.complete) + "/" + std::to_string(p.trials.size());
  if (warned > 0) s += ", " + std::to_string(warned) + (warned == 1 ? " warning" : " warnings");
  return s;
}

// "lr=0.05 momentum=0.5": a trial's swept values.
std::string values_text(const SweepPlan& plan, std::size_t trial) {
  std::string values;
  for (std::size_t k = 0; k < plan.keys.size(); ++k) {
    values += (k ? " " : "") + plan.keys[k] + "=" + plan.trials[trial].values[k];
  }
  return values;
}

}  // namespace

void print_summary(std::ostream& out, const SweepPlan& plan,
                   const std::vector<TrialOutcome>& outcomes, const SweepSummary& s,
                   const fs::path& dir, const std::string& name) {
  const std::string& objective = plan.objective.metric;
  TextTable table;
  table.header = {"rank"};
  for (const auto& k : plan.keys) table.header.push_back(k);
  table.header.push_back(objective + (plan.objective.maximize ? " (max)" : " (min)"));
  table.header.push_back("ok/runs");
  for (const auto& m : plan.metrics) {
    if (m != objective) table.header.push_back(m);
  }
  for (std::size_t r = 0; r < s.points.size(); ++r) {
    const PointStats& p = s.points[r];
    std::vector<std::string> row = {std::to_string(r + 1)};
    row.insert(row.end(), p.values.begin(), p.values.end());
    row.push_back(mean_std_text(p, objective));
    row.push_back(ok_runs_text(p, outcomes));
    for (const auto& m : plan.metrics) {
      if (m != objective) row.push_back(mean_std_text(p, m));
    }
    table.rows.push_back(std::move(row));
  }
  out << "== sweep "
      << (name.empty() || name == plan.experiment ? plan.experiment
                                                  : name + " (experiment " + plan.experiment + ")")
      << ": " << plan.trials.size() << " trials (" << s.points.size() << " points x "
      << plan.repeats << " repeats, " << plan.method << "); " << s.complete << " complete, "
      << s.failed + s.errors << " failed";
  if (s.missing) out << ", " << s.missing << " not run";
  out << " ==\n";
  table.print_aligned(out);
  for (std::size_t i = 0; i < plan.trials.size(); ++i) {
    const auto st = outcomes[i].status;
    if (st == TrialOutcome::Status::failed || st == TrialOutcome::Status::error) {
      out << "FAILED trial " << plan.trials[i].id << " (" << values_text(plan, i) << ", repeat "
          << plan.trials[i].repeat << "): " << outcomes[i].reason << "\n";
    }
  }
  for (std::size_t i = 0; i < plan.trials.size(); ++i) {
    for (const auto& w : outcomes[i].warnings) {
      out << "WARNING trial " << plan.trials[i].id << " (" << values_text(plan, i) << ", repeat "
          << plan.trials[i].repeat << "): " << w << "\n";
    }
  }
  if (s.best_trial >= 0) {
    const auto i = static_cast<std::size_t>(s.best_trial);
    out << "best trial: " << (dir / outcomes[i].result_file).string() << "  " << objective << " "
        << format_metric(metric_or_nan(outcomes[i].metrics, objective)) << " (" << kBestTrialRule
        << ", " << s.points.front().complete << " complete)";
    for (const auto& w : outcomes[i].warnings) out << "; warning: " << w;
    out << "\n";
  }
}

}  // namespace cnclab
