#include "cnclab/report/sweep_report.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "cnclab/nn/metrics.hpp"
#include "cnclab/report/text_table.hpp"
#include "cnclab/sweep/search_findings.hpp"

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
  const std::map<std::string, std::string> units = metric_units(outcomes);
  const auto with_unit = [&](const std::string& metric) {
    const auto it = units.find(metric);
    return it == units.end() || it->second.empty() ? metric : metric + " [" + it->second + "]";
  };
  // The ranking's split only: the other splits' numbers of every point are
  // in summary.h5; the test numbers are reported for the chosen point below.
  std::vector<std::string> shown;
  for (const auto& m : plan.metrics) {
    if (m != objective && metric_split(m) == metric_split(objective)) shown.push_back(m);
  }
  TextTable table;
  table.header = {"rank"};
  for (const auto& k : plan.keys) table.header.push_back(k);
  table.header.push_back(with_unit(objective) + (plan.objective.maximize ? " (max)" : " (min)"));
  table.header.push_back("ok/runs");
  for (const auto& m : shown) table.header.push_back(with_unit(m));
  for (std::size_t r = 0; r < s.points.size(); ++r) {
    const PointStats& p = s.points[r];
    std::vector<std::string> row = {std::to_string(r + 1)};
    row.insert(row.end(), p.values.begin(), p.values.end());
    row.push_back(mean_std_text(p, objective));
    row.push_back(ok_runs_text(p, outcomes));
    for (const auto& m : shown) row.push_back(mean_std_text(p, m));
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
    const PointStats& chosen = s.points.front();
    const std::vector<std::string> tested = test_metrics(plan);
    if (tested.empty()) {
      out << "chosen point, test: none (" << kNoTestSplitNote << ")\n";
    } else {
      out << "chosen point, test (rank 1, chosen by " << objective << "; reported after the "
          << "choice, mean ± std over its " << chosen.complete << " complete repeat"
          << (chosen.complete == 1 ? "" : "s") << "):\n";
      std::size_t width = 0;
      for (const auto& m : tested) width = std::max(width, with_unit(m).size());
      for (const auto& m : tested) {
        out << "  " << with_unit(m) << std::string(width - with_unit(m).size() + 2, ' ')
            << mean_std_text(chosen, m) << "\n";
      }
    }
  }
  if (const std::string w = objective_warning(plan); !w.empty()) out << "WARNING " << w << "\n";
}

void print_stored_summary(const std::filesystem::path& file, std::ostream& out) {
  const StoredSummary stored = read_summary(file);
  const SweepSummary summary = summarize(stored.plan, stored.outcomes);
  print_summary(out, stored.plan, stored.outcomes, summary, file.parent_path());
  if (stored.search) print_search_findings(out, *stored.search);
  const std::string best = summary.best_trial >= 0
                               ? stored.plan.trials[static_cast<std::size_t>(summary.best_trial)].id
                               : "";
  if (best != stored.best_trial) {
    out << "note: the file records best trial '" << stored.best_trial
        << "' (chosen by an older rule); `cnclab sweep merge` rewrites it\n";
  }
}

}  // namespace cnclab
