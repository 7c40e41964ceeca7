#include "cnclab/studies/step_error/step_error_measures.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "cnclab/report/statistics.hpp"
#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace {

// Table 2's figures over seeds (run_figures), and its two evaluations of one
// network: the measures' suffix and the inference.
const char* const kTable2Figures[] = {
    "test_mse",    "validation_mse",   "test_mse_deterministic", "validation_mse_deterministic",
    "test_mse_mc", "validation_mse_mc"};
const std::pair<const char*, DropoutInference> kTable2Evaluations[] = {
    {"", DropoutInference::deterministic}, {"_mc", DropoutInference::mc}};

void add_run(Measurements& m, const std::string& prefix, const StepErrorRun& r) {
  for (const auto& [name, value] : run_figures(r)) m[prefix + "." + name] = value;
}

// Mean, std and n of each figure over a point's seeds, under `prefix`.
void add_seeds(Measurements& m, const std::string& prefix, const RepeatedPoint& point) {
  if (point.runs.empty()) return;
  for (const auto& [name, value] : point.runs.front()) {
    const SampleSummary s = summarize(point.sample(name));
    m[prefix + "." + name + ".mean"] = s.mean;
    m[prefix + "." + name + ".std"] = s.std;
    m[prefix + "." + name + ".n"] = static_cast<double>(s.n);
  }
}

void add_repeats(Measurements& m, const StepErrorRepeats& r) {
  const std::string prefix = r.variant + ".seeds.";
  for (const auto& point : r.table2.points) {
    RepeatedPoint mse = point;
    for (auto& figures : mse.runs) {
      std::map<std::string, double> kept;
      for (const char* f : kTable2Figures) kept[f] = figures.at(f);
      figures = std::move(kept);
    }
    add_seeds(m, prefix + "table2.p" + table_number(point.number()), mse);
  }
  const auto p_of = [](const RepeatedPoint* point) { return point ? point->number() : NAN; };
  for (const auto& [suffix, figures] : {std::pair{"", "_deterministic"}, std::pair{"_mc", "_mc"}}) {
    const std::string best = prefix + "table2.best_p" + suffix;
    m[best] = p_of(table2_choice_over_seeds(r.table2, std::string("validation_mse") + figures));
    m[best + "_on_test"] =
        p_of(table2_choice_over_seeds(r.table2, std::string("test_mse") + figures));
  }
  for (const auto& point : r.surface1.points) add_seeds(m, prefix + "surface1", point);
  for (const auto* sweep : {&r.surface2_ft15, &r.surface3_ft15}) {
    const std::string surface = sweep == &r.surface2_ft15 ? "surface2" : "surface3";
    for (const auto& point : sweep->points) {
      add_seeds(m, prefix + surface + ".ft15." + point.value, point);
    }
  }
}

// Table 2 of one variant: validation and test MSE per keep probability under
// each evaluation, and the chosen p (table2_choice, as the table's notes).
void add_table2(Measurements& m, const std::string& variant, const StepErrorStudy& s,
                const StudyVariant& v) {
  for (const auto& [p, file] : v.table2) {
    const StepErrorRun& run = s.at(file);
    const std::string key = variant + ".table2.p" + table_number(p);
    const bool diverged = !run.failure.empty();
    m[key + ".diverged"] = diverged ? 1.0 : 0.0;
    for (const auto& [suffix, inference] : kTable2Evaluations) {
      m[key + ".test_mse" + suffix] = inference_test_mse(run, inference);
      m[key + ".validation_mse" + suffix] = inference_validation_mse(run, inference);
    }
  }
  for (const auto& [suffix, inference] : kTable2Evaluations) {
    const Table2Choice choice = table2_choice(s, v, inference);
    m[variant + ".table2.best_p" + suffix] = choice.on_validation;
    m[variant + ".table2.best_p" + suffix + "_on_test"] = choice.on_test;
  }
}

}  // namespace

double validation_mse(const RunRecord& r) {
  const auto it = r.metrics.find("validation.normalised_mse");
  return it == r.metrics.end() ? NAN : it->second;
}

Table2Choice table2_choice(const StepErrorStudy& s, const StudyVariant& v,
                           DropoutInference inference) {
  Table2Choice c;
  double best_validation = NAN, best_test = NAN;
  for (const auto& [p, file] : v.table2) {
    const StepErrorRun& run = s.at(file);
    if (!run.failure.empty()) continue;
    const double val = inference_validation_mse(run, inference);
    const double test = inference_test_mse(run, inference);
    if (!std::isnan(val) && !(val >= best_validation)) best_validation = val, c.on_validation = p;
    if (!std::isnan(test) && !(test >= best_test)) best_test = test, c.on_test = p;
  }
  return c;
}

// As Tables 3-7 and the normaliser table print them (step_error_tables.cpp:
// the rows' lambdas).
std::map<std::string, double> run_figures(const StepErrorRun& r) {
  const ErrorFigures& f = r.figures;
  const auto& h = r.record.training.history;
  return {{"test_samples", static_cast<double>(f.samples)},
          {"max_abs_um", f.max_abs},
          {"mean_abs_um", f.mean_abs},
          {"share_abs_below_0.4um", f.share_abs_below(0.4)},
          {"share_abs_below_0.5um", f.share_abs_below(0.5)},
          {"share_abs_below_1um", f.share_abs_below(1.0)},
          {"share_rel_below_10pct", f.share_rel_below(10)},
          {"share_rel_above_10pct", 100.0 - f.share_rel_below(10)},
          {"final_train_loss", h.empty() ? NAN : h.back().train_loss},
          {"test_mse", normalised_test_mse(r.record)},
          {"validation_mse", validation_mse(r.record)},
          {"test_mse_deterministic", inference_test_mse(r, DropoutInference::deterministic)},
          {"validation_mse_deterministic",
           inference_validation_mse(r, DropoutInference::deterministic)},
          {"test_mse_mc", inference_test_mse(r, DropoutInference::mc)},
          {"validation_mse_mc", inference_validation_mse(r, DropoutInference::mc)},
          {"mc_samples", static_cast<double>(r.record.model.dropout_mc_samples)}};
}

Measurements step_error_measures(const StepErrorStudy& s) {
  Measurements m;
  for (const auto& v : s.manifest.variants) {
    add_table2(m, v.name, s, v);
    add_run(m, v.name + ".surface1", s.at(v.surface1));
    add_run(m, v.name + ".surface1_no_dropout", s.at(v.surface1_no_dropout));
    for (const auto& [pct, file] : v.surface2) {
      add_run(m, v.name + ".surface2.ft" + table_number(pct), s.at(file));
    }
    for (const auto& [pct, file] : v.surface3) {
      add_run(m, v.name + ".surface3.ft" + table_number(pct), s.at(file));
    }
  }
  for (const auto& n : s.manifest.normaliser) {
    add_run(m, "normaliser." + n.name + ".surface2", s.at(n.surface2));
    add_run(m, "normaliser." + n.name + ".surface3", s.at(n.surface3));
  }
  if (s.repeats) add_repeats(m, *s.repeats);
  return m;
}

Measurements measure_step_error_tables(const TablesOptions& options) {
  return step_error_measures(load_step_error_study(options));
}

}  // namespace cnclab
