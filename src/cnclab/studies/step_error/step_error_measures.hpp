#pragma once
// The step-error tables' numbers by name, for the targets of
// configs/studies/step_error_tables.yaml (report/targets.hpp). Each is the
// figure a table row prints, from the same ErrorFigures (step_error_stats.hpp)
// and normalised_test_mse calls:
//
//   <variant>.table2.p<p>.test_mse          Table 2, test MSE (z-score units)
//   <variant>.table2.p<p>.validation_mse    Table 2, validation MSE (z-score units)
//   <variant>.table2.p<p>.<test|validation>_mse_mc   the same network evaluated by MC dropout
//                                           (the two above: evaluated deterministically)
//   <variant>.table2.p<p>.diverged          1 when that training diverged, else 0
//   <variant>.table2.best_p                 the chosen keep probability: lowest validation MSE
//                                           (deterministic evaluation)
//   <variant>.table2.best_p_on_test         the lowest test MSE's (the paper's reading, shown
//                                           beside the choice, never used for it)
//   <variant>.table2.best_p_mc, best_p_mc_on_test   the same two under MC dropout
//   <variant>.<run>.<figure>                run: surface1, surface1_no_dropout,
//                                           surface2.ft<percent>, surface3.ft<percent>
//   normaliser.<keep|refit>.<surface2|3>.<figure>
//
// with <figure> one of test_samples, max_abs_um, mean_abs_um,
// share_abs_below_0.4um, share_abs_below_0.5um, share_abs_below_1um (%),
// share_rel_below_10pct, share_rel_above_10pct (%), final_train_loss (z-score
// units, last epoch), test_mse and validation_mse (z-score units, Table 2's;
// as the run reports them, model.dropout.inference; validation_mse NaN
// without a validation split), <test|validation>_mse_<deterministic|mc> (the
// network evaluated each way; NaN when the result lacks that evaluation),
// mc_samples (the masks MC dropout averages, model.dropout.mc_samples). <p>
// and <percent> as the tables print them (0.5, 15).
//
// Over the seeds of the manifest's `repeats:` (step_error_repeats.hpp), for
// its variant:
//   <variant>.seeds.surface1.<figure>.{mean,std,n}            surface 1 (keep 1.0, 70/30)
//   <variant>.seeds.table2.p<p>.<test|validation>_mse[_<deterministic|mc>].{mean,std,n}
//                                                              (p 1: no dropout)
//   <variant>.seeds.table2.best_p, best_p_on_test             table2_choice_over_seeds,
//                                                              deterministic evaluation
//   <variant>.seeds.table2.best_p_mc, best_p_mc_on_test       the same under MC dropout
//   <variant>.seeds.<surface2|surface3>.ft15.<keep|refit>.<figure>.{mean,std,n}
// (std over the seeds, n - 1; n the complete trials).
#include <cmath>
#include <map>
#include <string>

#include "cnclab/report/tables.hpp"
#include "cnclab/studies/step_error/step_error_study.hpp"

namespace cnclab {

// The <figure>s above of one complete run, by name.
std::map<std::string, double> run_figures(const StepErrorRun& run);

// A run's validation MSE in the z-score units of its targets: its
// validation.normalised_mse metric; NaN without one (no validation split).
double validation_mse(const RunRecord& record);

// Table 2's choice of keep probability for one variant, one run per p, over
// the trainings that did not diverge, each network evaluated by `inference`:
// the lowest validation MSE (the choice), and beside it the lowest test MSE
// (the paper's reading, which chooses on the data it reports). NaN when no
// run has the MSE.
struct Table2Choice {
  double on_validation = NAN, on_test = NAN;
};
Table2Choice table2_choice(const StepErrorStudy& study, const StudyVariant& variant,
                           DropoutInference inference);

Measurements step_error_measures(const StepErrorStudy& study);
// Loads the study (load_step_error_study) and measures it: TableEntry::measure.
Measurements measure_step_error_tables(const TablesOptions& options);

}  // namespace cnclab
