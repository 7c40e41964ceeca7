#include "cnclab/studies/step_error/step_error_repeats.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/report/statistics.hpp"
#include "cnclab/studies/step_error/step_error_measures.hpp"
#include "cnclab/sweep/sweep_job.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// A point's label: the swept value, or for an `init_from` mapping (the
// fine-tuning sweeps, whose keep and refit chains differ in upstream too)
// its `normaliser`.
std::string repeats_point_label(const std::string& value) {
  try {
    const YAML::Node node = YAML::Load(value);
    if (node.IsMap() && node["normaliser"]) return node["normaliser"].as<std::string>();
  } catch (const YAML::Exception&) {
  }
  return value;
}

}  // namespace

double RepeatedPoint::number() const {
  try {
    std::size_t used = 0;
    const double v = std::stod(value, &used);
    return used == value.size() ? v : NAN;
  } catch (const std::exception&) {
    return NAN;
  }
}

std::vector<double> RepeatedPoint::sample(const std::string& figure) const {
  std::vector<double> out;
  for (const auto& r : runs) {
    const auto it = r.find(figure);
    if (it != r.end() && !std::isnan(it->second)) out.push_back(it->second);
  }
  return out;
}

const RepeatedPoint* RepeatedSweep::find(const std::string& value) const {
  for (const auto& p : points) {
    if (p.value == value) return &p;
  }
  return nullptr;
}

const RepeatedPoint* RepeatedSweep::find(double number) const {
  for (const auto& p : points) {
    if (p.number() == number) return &p;
  }
  return nullptr;
}

const RepeatedPoint* table2_choice_over_seeds(const RepeatedSweep& table2,
                                              const std::string& figure) {
  const RepeatedPoint* best = nullptr;
  double best_mean = NAN;
  for (const auto& point : table2.points) {
    const std::vector<double> v = point.sample(figure);
    if (point.number() == kNoDropout || v.size() < 2) continue;
    const double mean = summarize(v).mean;
    if (!best || mean < best_mean) best = &point, best_mean = mean;
  }
  return best;
}

RepeatedSweep load_repeated_sweep(const fs::path& file, const TablesOptions& o) {
  if (!fs::exists(file)) throw MissingResults(file.string() + ": not found");
  const SweepJob job = load_sweep_job(file, {}, o.profile);
  const SweepJobState state = sweep_job_state(job, o.results_dir);
  if (state.plan.keys.size() != 1) {
    throw ConfigError(file.string() + ": a seed sweep of the step-error study varies one key (" +
                      std::to_string(state.plan.keys.size()) + " here)");
  }
  if (state.summary.missing > 0) {
    const ResultStore store(o.results_dir, o.profile);
    throw MissingResults(std::to_string(state.summary.missing) + " of " +
                         std::to_string(state.plan.trials.size()) + " trials of " + file.string() +
                         " have no result under " + state.dir.string() + "; run `" +
                         store.make_command(sweep_job_key(job, state.plan)) + "` first");
  }
  RepeatedSweep out;
  out.file = file;
  out.dir = state.dir;
  out.key = state.plan.keys.front();
  std::vector<fs::path> paths;  // the complete trials' results, in plan order
  for (const TrialOutcome& outcome : state.outcomes) {
    if (outcome.status == TrialOutcome::Status::complete) {
      paths.push_back(state.dir / outcome.result_file);
    }
  }
  std::vector<ReadOutcome<RunRecord>> records = read_results(paths);
  for (std::size_t i = 0, k = 0; i < state.plan.trials.size(); ++i) {
    const PlannedTrial& t = state.plan.trials[i];
    if (t.point >= out.points.size()) {
      out.points.resize(t.point + 1);
      out.points[t.point].value = repeats_point_label(t.values.front());
    }
    RepeatedPoint& point = out.points[t.point];
    ++point.planned;
    if (state.outcomes[i].status != TrialOutcome::Status::complete) continue;
    const fs::path& path = paths[k];
    const StepErrorRun run = step_error_run(std::move(records[k++]).get(), path);
    point.runs.push_back(run_figures(run));
    point.seeds.push_back(t.seed);
    out.sources.push_back(path);
    out.configs.push_back(run.record.resolved_yaml);
  }
  return out;
}

StepErrorRepeats load_step_error_repeats(const StudyRepeats& r, const TablesOptions& o) {
  return {r.variant, load_repeated_sweep(r.table2, o), load_repeated_sweep(r.surface1, o),
          load_repeated_sweep(r.surface2_ft15, o), load_repeated_sweep(r.surface3_ft15, o)};
}

}  // namespace cnclab
