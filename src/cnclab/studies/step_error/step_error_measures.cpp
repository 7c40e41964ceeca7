#include "cnclab/studies/step_error/step_error_measures.hpp"

#include <cmath>
#include <string>

#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace {

// The figures of one run under `prefix`, as Tables 3-7 and the normaliser
// table print them (step_error_tables.cpp: the rows' lambdas).
void add_run(Measurements& m, const std::string& prefix, const StepErrorRun& r) {
  const ErrorFigures& f = r.figures;
  m[prefix + ".test_samples"] = static_cast<double>(f.samples);
  m[prefix + ".max_abs_um"] = f.max_abs;
  m[prefix + ".mean_abs_um"] = f.mean_abs;
  m[prefix + ".share_abs_below_0.4um"] = f.share_abs_below(0.4);
  m[prefix + ".share_abs_below_0.5um"] = f.share_abs_below(0.5);
  m[prefix + ".share_abs_below_1um"] = f.share_abs_below(1.0);
  m[prefix + ".share_rel_below_10pct"] = f.share_rel_below(10);
  m[prefix + ".share_rel_above_10pct"] = 100.0 - f.share_rel_below(10);
  const auto& h = r.record.training.history;
  m[prefix + ".final_train_loss"] = h.empty() ? NAN : h.back().train_loss;
}

// Table 2 of one variant: test MSE per keep probability, and the best p
// (lowest test MSE of the trainings that did not diverge, as the table's note).
void add_table2(Measurements& m, const std::string& variant, const StepErrorStudy& s,
                const StudyVariant& v) {
  double best = NAN, best_p = NAN;
  for (const auto& [p, file] : v.table2) {
    const StepErrorRun& run = s.at(file);
    const std::string key = variant + ".table2.p" + table_number(p);
    const bool diverged = !run.failure.empty();
    const double mse = diverged ? NAN : normalised_test_mse(run.record);
    m[key + ".diverged"] = diverged ? 1.0 : 0.0;
    m[key + ".test_mse"] = mse;
    if (!std::isnan(mse) && !(mse >= best)) {
      best = mse;
      best_p = p;
    }
  }
  m[variant + ".table2.best_p"] = best_p;
}

}  // namespace

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
  return m;
}

Measurements measure_step_error_tables(const TablesOptions& options) {
  return step_error_measures(load_step_error_study(options));
}

}  // namespace cnclab
