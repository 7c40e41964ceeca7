#include "cnclab/sweep/sweep_summary.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/run_warnings.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/file_format.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/isolated_read.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/sweep/trial_pool.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr int kSummaryVersion = 2;  // 1: metric names of result format 1 (sweep_summary.hpp)
const double kNaN = std::nan("");

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  std::string s = ss.str();
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

// True if a ranks before b under the objective (NaN last).
bool better(double a, double b, bool maximize) {
  if (std::isnan(b)) return !std::isnan(a);
  if (std::isnan(a)) return false;
  return maximize ? a > b : a < b;
}

// The median repeat of a point by the objective, among its complete trials:
// of n ranked best first, the one at (n - 1) / 2, so for an even n the better
// of the two middle ones. A trial of the best point, typical of it: the best
// single trial of a sweep may be a lucky repeat of a worse point.
std::size_t median_trial(const SweepPlan& plan, const std::vector<TrialOutcome>& outcomes,
                         const PointStats& point) {
  std::vector<std::size_t> done;
  for (std::size_t i : point.trials) {
    if (outcomes[i].status == TrialOutcome::Status::complete) done.push_back(i);
  }
  const std::string& objective = plan.objective.metric;
  std::stable_sort(done.begin(), done.end(), [&](std::size_t a, std::size_t b) {
    return better(metric_or_nan(outcomes[a].metrics, objective),
                  metric_or_nan(outcomes[b].metrics, objective), plan.objective.maximize);
  });
  return done[(done.size() - 1) / 2];
}

bool parse_number(const std::string& s, double& v) {
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && ptr == s.data() + s.size() && !s.empty();
}

// A column of YAML value texts: numbers when all are, else the texts.
void write_values(H5File& f, const std::string& name, const std::vector<std::string>& texts) {
  std::vector<double> numbers;
  for (const auto& t : texts) {
    double v = 0;
    if (!parse_number(t, v)) {
      f.write_strings(name, texts);
      return;
    }
    numbers.push_back(v);
  }
  f.write_vector(name, numbers);
}

// "id1,id2,...": a point's trials in repeat order (their result files are
// trials/<id>.h5 in the sweep folder).
// <group>/parameters/<key>: each row's swept value of every key (rows:
// planned trials or points, both with `values` in plan.keys order).
template <class Rows>
void write_parameters(H5File& f, const std::string& group, const SweepPlan& plan,
                      const Rows& rows) {
  for (std::size_t k = 0; k < plan.keys.size(); ++k) {
    std::vector<std::string> texts;
    for (const auto& row : rows) texts.push_back(row.values[k]);
    write_values(f, group + "/parameters/" + plan.keys[k], texts);
  }
}

std::string trial_ids(const SweepPlan& plan, const PointStats& p) {
  std::string ids;
  for (std::size_t i : p.trials) ids += (ids.empty() ? "" : ",") + plan.trials[i].id;
  return ids;
}

}  // namespace

double metric_or_nan(const std::map<std::string, double>& m, const std::string& name) {
  const auto it = m.find(name);
  return it == m.end() ? kNaN : it->second;
}

std::map<std::string, std::string> metric_units(const std::vector<TrialOutcome>& outcomes) {
  std::map<std::string, std::string> units;
  for (const auto& o : outcomes) {
    for (const auto& [name, unit] : o.metric_units) {
      if (!unit.empty()) units.emplace(name, unit);
    }
  }
  return units;
}

std::vector<std::string> test_metrics(const SweepPlan& plan) {
  std::vector<std::string> names;
  for (const auto& m : plan.metrics) {
    if (metric_split(m) == "test") names.push_back(m);
  }
  return names;
}

std::string to_string(TrialOutcome::Status status) {
  switch (status) {
    case TrialOutcome::Status::complete:
      return "complete";
    case TrialOutcome::Status::failed:
      return "failed";
    case TrialOutcome::Status::error:
      return "error";
    case TrialOutcome::Status::missing:
      return "missing";
    case TrialOutcome::Status::pruned:
      return "pruned";
  }
  return "?";
}

namespace {

// A trial's outcome: from its result file's status when it has one (`read`:
// the status, or the error reading it), else from its error note.
TrialOutcome trial_outcome(const fs::path& dir, const PlannedTrial& trial,
                           ReadOutcome<ResultStatus>* read) {
  TrialOutcome o;
  std::error_code ec;
  if (read) {
    try {
      ResultStatus r = std::move(*read).get();
      o.result_file = fs::relative(trial_result_path(dir, trial.id), dir, ec).string();
      o.upstream = std::move(r.upstream);
      if (r.status == "complete") {
        o.status = TrialOutcome::Status::complete;
        o.metrics = std::move(r.metrics);
        o.metric_units = std::move(r.metric_units);
        o.warnings = std::move(r.warnings);
      } else if (r.status == "pruned") {
        o.status = TrialOutcome::Status::pruned;
        o.reason = r.failure_reason;
      } else {
        o.status = TrialOutcome::Status::failed;
        o.reason = r.failure_reason;
      }
      return o;
    } catch (const IoError& e) {
      o.reason = std::string("unreadable result: ") + e.what();
      return o;  // missing: run again
    }
  }
  const fs::path note = trial_error_path(dir, trial.id);
  if (fs::exists(note, ec)) {
    o.reason = read_text(note);
    // A timed-out trial is a failure of its config (too slow), not of the run.
    o.status = o.reason.rfind(kTimeoutNote, 0) == 0 ? TrialOutcome::Status::failed
                                                    : TrialOutcome::Status::error;
  }
  return o;
}

}  // namespace

TrialOutcome read_trial_outcome(const fs::path& dir, const PlannedTrial& trial) {
  const fs::path result = trial_result_path(dir, trial.id);
  std::error_code ec;
  if (!fs::exists(result, ec)) return trial_outcome(dir, trial, nullptr);
  return trial_outcome(dir, trial, &read_result_statuses({result}).front());
}

std::vector<TrialOutcome> read_trial_outcomes(const fs::path& dir, const SweepPlan& plan) {
  const std::vector<PlannedTrial>& trials = plan.trials;
  std::vector<fs::path> results;
  std::vector<std::size_t> with_result;  // trials[with_result[k]] has results[k]
  for (std::size_t i = 0; i < trials.size(); ++i) {
    const fs::path result = trial_result_path(dir, trials[i].id);
    std::error_code ec;
    if (fs::exists(result, ec)) {
      results.push_back(result);
      with_result.push_back(i);
    }
  }
  std::vector<ReadOutcome<ResultStatus>> read = read_result_statuses(results);
  std::vector<TrialOutcome> out;
  for (std::size_t i = 0, k = 0; i < trials.size(); ++i) {
    const bool has_result = k < with_result.size() && with_result[k] == i;
    out.push_back(trial_outcome(dir, trials[i], has_result ? &read[k++] : nullptr));
  }
  return out;
}

SweepSummary summarize(const SweepPlan& plan, const std::vector<TrialOutcome>& outcomes) {
  SweepSummary s;
  std::map<std::size_t, PointStats> points;
  const std::string& objective = plan.objective.metric;
  for (std::size_t i = 0; i < plan.trials.size(); ++i) {
    const PlannedTrial& t = plan.trials[i];
    const TrialOutcome& o = outcomes[i];
    PointStats& p = points[t.point];
    p.point = t.point;
    p.values = t.values;
    p.trials.push_back(i);
    switch (o.status) {
      case TrialOutcome::Status::complete:
        ++s.complete, ++p.complete;
        break;
      case TrialOutcome::Status::failed:
        ++s.failed, ++p.failed;
        break;
      case TrialOutcome::Status::error:
        ++s.errors, ++p.failed;
        break;
      case TrialOutcome::Status::missing:
        ++s.missing, ++p.missing;
        break;
      case TrialOutcome::Status::pruned:
        ++s.pruned, ++p.pruned;
        break;
    }
  }
  for (auto& [index, p] : points) {
    for (const auto& metric : plan.metrics) {
      double sum = 0, sum_sq = 0;
      std::size_t n = 0;
      for (std::size_t i : p.trials) {
        if (outcomes[i].status != TrialOutcome::Status::complete) continue;
        const double v = metric_or_nan(outcomes[i].metrics, metric);
        sum += v;
        ++n;
      }
      if (n == 0) continue;
      const double mean = sum / static_cast<double>(n);
      for (std::size_t i : p.trials) {
        if (outcomes[i].status != TrialOutcome::Status::complete) continue;
        const double d = metric_or_nan(outcomes[i].metrics, metric) - mean;
        sum_sq += d * d;
      }
      p.mean[metric] = mean;
      p.std[metric] = n >= 2 ? std::sqrt(sum_sq / static_cast<double>(n - 1)) : kNaN;
    }
    s.points.push_back(p);
  }
  std::stable_sort(s.points.begin(), s.points.end(), [&](const PointStats& a, const PointStats& b) {
    return better(metric_or_nan(a.mean, objective), metric_or_nan(b.mean, objective),
                  plan.objective.maximize);
  });
  if (!s.points.empty() && s.points.front().complete > 0) {
    s.best_trial = static_cast<std::ptrdiff_t>(median_trial(plan, outcomes, s.points.front()));
  }
  return s;
}

void write_summary(const fs::path& file, const SweepPlan& plan,
                   const std::vector<TrialOutcome>& outcomes, const SweepSummary& s,
                   const SearchFindings* search) {
  AtomicOutput out(file);
  try {
    H5File f = H5File::create(out.temp_path());
    write_format(f, kSummaryFormat, kSummaryVersion);
    f.set_attribute("/", "experiment", plan.experiment);
    f.set_attribute("/", "method", plan.method);
    f.set_attribute("/", "repeats", static_cast<std::int64_t>(plan.repeats));
    f.set_attribute("/", "objective_metric", plan.objective.metric);
    f.set_attribute("/", "objective_mode", plan.objective.maximize ? "max" : "min");
    f.set_attribute("/", "plan_hash", plan.hash());
    f.set_attribute("/", "trials", static_cast<std::int64_t>(plan.trials.size()));
    f.set_attribute("/", "complete_trials", static_cast<std::int64_t>(s.complete));
    f.set_attribute("/", "failed", static_cast<std::int64_t>(s.failed));
    f.set_attribute("/", "errors", static_cast<std::int64_t>(s.errors));
    f.set_attribute("/", "missing", static_cast<std::int64_t>(s.missing));
    f.set_attribute("/", "pruned", static_cast<std::int64_t>(s.pruned));
    if (s.best_trial >= 0) {
      f.set_attribute("/", "best_trial", plan.trials[static_cast<std::size_t>(s.best_trial)].id);
      f.set_attribute("/", "best_trial_rule", std::string(kBestTrialRule));
    }
    f.write_string("/plan", plan.to_yaml());

    std::vector<std::string> id, status, reason, result, seed, warnings;
    std::vector<std::int64_t> point, repeat;
    for (std::size_t i = 0; i < plan.trials.size(); ++i) {
      const PlannedTrial& t = plan.trials[i];
      id.push_back(t.id);
      status.push_back(to_string(outcomes[i].status));
      reason.push_back(outcomes[i].reason);
      result.push_back(outcomes[i].result_file);
      warnings.push_back(join_warnings(outcomes[i].warnings));
      seed.push_back(std::to_string(t.seed));
      point.push_back(static_cast<std::int64_t>(t.point));
      repeat.push_back(static_cast<std::int64_t>(t.repeat));
    }
    f.write_strings("/trials/id", id);
    f.write_strings("/trials/status", status);
    f.write_strings("/trials/reason", reason);
    f.write_strings("/trials/result_file", result);
    f.write_strings("/trials/warnings", warnings);
    f.write_strings("/trials/seed", seed);
    f.write_int64s("/trials/point", point);
    f.write_int64s("/trials/repeat", repeat);
    write_parameters(f, "/trials", plan, plan.trials);
    const std::map<std::string, std::string> units = metric_units(outcomes);
    const auto unit_of = [&](const std::string& metric) {
      const auto it = units.find(metric);
      return it == units.end() ? std::string() : it->second;
    };
    for (const auto& metric : plan.metrics) {
      std::vector<double> v;
      for (const auto& o : outcomes) v.push_back(metric_or_nan(o.metrics, metric));
      f.write_vector("/trials/metrics/" + metric, v, unit_of(metric));
    }

    std::vector<std::int64_t> p_index, p_complete, p_failed;
    std::vector<std::string> p_trials;
    for (const auto& p : s.points) {
      p_index.push_back(static_cast<std::int64_t>(p.point));
      p_complete.push_back(static_cast<std::int64_t>(p.complete));
      p_failed.push_back(static_cast<std::int64_t>(p.failed));
      p_trials.push_back(trial_ids(plan, p));
    }
    f.write_int64s("/points/point", p_index);
    f.write_strings("/points/trials", p_trials);
    f.write_int64s("/points/complete", p_complete);
    f.write_int64s("/points/failed", p_failed);
    write_parameters(f, "/points", plan, s.points);
    for (const auto& metric : plan.metrics) {
      std::vector<double> mean, sd;
      for (const auto& p : s.points) {
        mean.push_back(metric_or_nan(p.mean, metric));
        sd.push_back(metric_or_nan(p.std, metric));
      }
      f.write_vector("/points/metrics/" + metric + "/mean", mean);
      f.write_vector("/points/metrics/" + metric + "/std", sd);
    }
    if (s.best_trial >= 0) {
      const PointStats& chosen = s.points.front();
      f.create_group("/selected");
      f.set_attribute("/selected", "point", static_cast<std::int64_t>(chosen.point));
      f.set_attribute("/selected", "trial", plan.trials[static_cast<std::size_t>(s.best_trial)].id);
      f.set_attribute("/selected", "objective_metric", plan.objective.metric);
      f.set_attribute("/selected", "complete", static_cast<std::int64_t>(chosen.complete));
      for (const char* g : {"/selected/metrics", "/selected/metrics_std", "/selected/units"}) {
        f.create_group(g);
      }
      const std::vector<std::string> tested = test_metrics(plan);
      if (tested.empty()) f.set_attribute("/selected", "note", std::string(kNoTestSplitNote));
      for (const auto& metric : tested) {
        f.set_attribute("/selected/metrics", metric, metric_or_nan(chosen.mean, metric));
        f.set_attribute("/selected/metrics_std", metric, metric_or_nan(chosen.std, metric));
        f.set_attribute("/selected/units", metric, unit_of(metric));
      }
    }
    if (search) write_search_findings(f, *search);
    mark_complete(f);  // last
    f.close();
    out.commit();
  } catch (const IoError& e) {
    throw IoError(file.string() + ": sweep summary not written: " + std::string(e.what()));
  }
}

namespace {

TrialOutcome::Status parse_status(const std::string& text, const fs::path& file) {
  for (const auto s :
       {TrialOutcome::Status::complete, TrialOutcome::Status::failed, TrialOutcome::Status::error,
        TrialOutcome::Status::missing, TrialOutcome::Status::pruned}) {
    if (to_string(s) == text) return s;
  }
  throw IoError(file.string() + ": /trials/status: unknown status '" + text + "'");
}

StoredSummary read_summary_in_process(const fs::path& file) {
  const H5File f = H5File::open_read(file);
  const int version = require_format(f, kSummaryFormat, 1, kSummaryVersion);
  StoredSummary s;
  s.plan = parse_plan(f.read_string("/plan"), file.string() + ":/plan");
  // Each of the plan's metrics (today's names) as the summary stores it.
  std::map<std::string, std::string> stored_as;
  for (const auto& m : s.plan.metrics) stored_as[m] = m;
  if (version == 1 && f.is_group("/trials/metrics")) {
    for (const auto& name : f.children("/trials/metrics")) {
      stored_as[format1_metric_name(name)] = name;
    }
  }
  const std::size_t n = s.plan.trials.size();
  const auto ids = f.read_strings("/trials/id");
  const auto status = f.read_strings("/trials/status");
  const auto reason = f.read_strings("/trials/reason");
  const auto result = f.read_strings("/trials/result_file");
  // Summaries written before warnings existed have none.
  const auto warnings = f.exists("/trials/warnings") ? f.read_strings("/trials/warnings")
                                                     : std::vector<std::string>(n);
  for (const auto* column : {&ids, &status, &reason, &result, &warnings}) {
    if (column->size() != n) {
      throw IoError(file.string() + ": /trials: " + std::to_string(column->size()) +
                    " rows for the plan's " + std::to_string(n) + " trials");
    }
  }
  std::map<std::string, std::vector<double>> metrics;
  std::map<std::string, std::string> units;
  for (const auto& m : s.plan.metrics) {
    const std::string name = "/trials/metrics/" + stored_as[m];
    metrics[m] = f.read_vector(name);
    if (metrics[m].size() != n) throw IoError(file.string() + ":" + name + ": size");
    if (f.has_attribute(name, "units")) units[m] = f.units(name);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (ids[i] != s.plan.trials[i].id) {
      throw IoError(file.string() + ": /trials/id: trial " + std::to_string(i) + " is " + ids[i] +
                    ", the plan says " + s.plan.trials[i].id);
    }
    TrialOutcome o;
    o.status = parse_status(status[i], file);
    o.reason = reason[i];
    o.result_file = result[i];
    if (o.status == TrialOutcome::Status::complete) {
      for (const auto& [m, v] : metrics) o.metrics[m] = v[i];
      o.metric_units = units;
      o.warnings = split_warnings(warnings[i]);
    }
    s.outcomes.push_back(std::move(o));
  }
  if (f.has_attribute("/", "best_trial")) s.best_trial = f.attribute_string("/", "best_trial");
  s.search = read_search_findings(f);
  return s;
}

}  // namespace

bool is_sweep_summary(const fs::path& file) {
  const auto read = [&] {
    const H5File f = H5File::open_read(file);
    return f.has_attribute("/", "format") && f.attribute_string("/", "format") == kSummaryFormat;
  };
  probe_in_child(file, [&] { read(); });
  return read();
}

StoredSummary read_summary(const fs::path& file) {
  probe_in_child(file, [&] { read_summary_in_process(file); });
  return read_summary_in_process(file);
}

}  // namespace cnclab
