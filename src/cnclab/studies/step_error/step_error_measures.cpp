#include "cnclab/studies/step_error/step_error_measures.hpp"

#include <cmath>
#include <string>

#include "cnclab/report/statistics.hpp"
#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace {

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
  for (const auto& point : r.surface1.points) {
    const double p = point.number();
    if (p == 1.0) {
      add_seeds(m, prefix + "surface1", point);
    } else {
      RepeatedPoint mse = point;
      for (auto& figures : mse.runs) {
        figures = {{"test_mse", figures.at("test_mse")},
                   {"test_mse_deterministic", figures.at("test_mse_deterministic")},
                   {"test_mse_mc", figures.at("test_mse_mc")}};
      }
      add_seeds(m, prefix + "table2.p" + table_number(p), mse);
    }
  }
  for (const auto* sweep : {&r.surface2_ft15, &r.surface3_ft15}) {
    const std::string surface = sweep == &r.surface2_ft15 ? "surface2" : "surface3";
    for (const auto& point : sweep->points) {
      add_seeds(m, prefix + surface + ".ft15." + point.value, point);
    }
  }
}

// Table 2 of one variant: test MSE per keep probability, and the best p
// (lowest test MSE of the trainings that did not diverge, as the table's note).
void add_table2(Measurements& m, const std::string& variant, const StepErrorStudy& s,
                const StudyVariant& v) {
  double best = NAN, best_p = NAN, best_mc = NAN, best_p_mc = NAN;
  const auto lower = [](double mse, double p, double& least, double& at) {
    if (!std::isnan(mse) && !(mse >= least)) {
      least = mse;
      at = p;
    }
  };
  for (const auto& [p, file] : v.table2) {
    const StepErrorRun& run = s.at(file);
    const std::string key = variant + ".table2.p" + table_number(p);
    const bool diverged = !run.failure.empty();
    const double mse = diverged ? NAN : normalised_test_mse(run.record);
    const double mc = inference_test_mse(run, DropoutInference::mc);
    m[key + ".diverged"] = diverged ? 1.0 : 0.0;
    m[key + ".test_mse"] = mse;
    m[key + ".test_mse_mc"] = mc;
    lower(mse, p, best, best_p);
    lower(mc, p, best_mc, best_p_mc);
  }
  m[variant + ".table2.best_p"] = best_p;
  m[variant + ".table2.best_p_mc"] = best_p_mc;
}

}  // namespace

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
          {"test_mse_deterministic", inference_test_mse(r, DropoutInference::deterministic)},
          {"test_mse_mc", inference_test_mse(r, DropoutInference::mc)},
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
