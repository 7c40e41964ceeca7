#pragma once
// The step-error tables' numbers by name, for the targets of
// configs/studies/step_error_tables.yaml (report/targets.hpp). Each is the
// figure a table row prints, from the same ErrorFigures (step_error_stats.hpp)
// and normalised_test_mse calls:
//
//   <variant>.table2.p<p>.test_mse          Table 2, test MSE (z-score units)
//   <variant>.table2.p<p>.test_mse_mc       the same network evaluated by MC dropout
//   <variant>.table2.p<p>.diverged          1 when that training diverged, else 0
//   <variant>.table2.best_p                 keep probability with the lowest test MSE
//   <variant>.table2.best_p_mc              the same under MC dropout
//   <variant>.<run>.<figure>                run: surface1, surface1_no_dropout,
//                                           surface2.ft<percent>, surface3.ft<percent>
//   normaliser.<keep|refit>.<surface2|3>.<figure>
//
// with <figure> one of test_samples, max_abs_um, mean_abs_um,
// share_abs_below_0.4um, share_abs_below_0.5um, share_abs_below_1um (%),
// share_rel_below_10pct, share_rel_above_10pct (%), final_train_loss (z-score
// units, last epoch), test_mse (z-score units, Table 2's; as the run reports
// it), test_mse_deterministic and test_mse_mc (the network evaluated each way;
// NaN when the result lacks that evaluation), mc_samples (the masks MC
// dropout averages, model.dropout.mc_samples). <p> and <percent>
// as the tables print them (0.5, 15).
//
// Over the seeds of the manifest's `repeats:` (step_error_repeats.hpp), for
// its variant:
//   <variant>.seeds.surface1.<figure>.{mean,std,n}            keep 1.0 (no dropout)
//   <variant>.seeds.table2.p<p>.<test_mse|test_mse_deterministic|test_mse_mc>.{mean,std,n}
//   <variant>.seeds.<surface2|surface3>.ft15.<keep|refit>.<figure>.{mean,std,n}
// (std over the seeds, n - 1; n the complete trials).
#include <map>
#include <string>

#include "cnclab/report/tables.hpp"
#include "cnclab/studies/step_error/step_error_study.hpp"

namespace cnclab {

// The <figure>s above of one complete run, by name.
std::map<std::string, double> run_figures(const StepErrorRun& run);

Measurements step_error_measures(const StepErrorStudy& study);
// Loads the study (load_step_error_study) and measures it: TableEntry::measure.
Measurements measure_step_error_tables(const TablesOptions& options);

}  // namespace cnclab
