#include "cnclab/studies/step_error/step_error_search.hpp"

#include <cmath>
#include <set>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/report/run_settings.hpp"
#include "cnclab/report/typed_table.hpp"
#include "cnclab/studies/step_error/step_error_study.hpp"
#include "cnclab/studies/step_error/step_error_table_parts.hpp"
#include "cnclab/sweep/sweep_job.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// Table 2's MSE: the objective both sweeps choose on, and its test twin.
constexpr const char* kValidation = "validation.normalised_mse";
constexpr const char* kTest = "test.normalised_mse";

// "key: N values" per swept key of a grid (its values from the plan).
std::string grid_space(const SweepPlan& plan) {
  std::string out;
  for (std::size_t k = 0; k < plan.keys.size(); ++k) {
    std::set<std::string> values;
    for (const auto& t : plan.trials) values.insert(t.values[k]);
    std::string listed;
    for (const auto& v : values) listed += (listed.empty() ? "" : ", ") + v;
    out += (out.empty() ? "" : "; ") + plan.keys[k] + " in {" + listed + "}";
  }
  return out;
}

}  // namespace

SearchedSpace load_searched_space(const fs::path& file, const TablesOptions& o) {
  if (!fs::exists(file)) throw MissingResults(file.string() + ": not found");
  const SweepJob job = load_sweep_job(file, {}, o.profile);
  const SweepJobState state = sweep_job_state(job, o.results_dir);
  SearchedSpace out;
  out.file = file;
  out.method = state.plan.method;
  out.pruner = state.plan.pruner;
  if (model_based(state.plan)) {
    for (const auto& p : state.plan.space) out.space += (out.space.empty() ? "" : ", ") + p;
  } else {
    out.space = grid_space(state.plan);
  }
  if (state.plan.trials.empty() || state.summary.complete == 0) {
    const ResultStore store(o.results_dir, o.profile);
    throw MissingResults(file.string() + ": no complete trial under " + state.dir.string() +
                         "; run `" + store.make_command(sweep_job_key(job, state.plan)) +
                         "` first");
  }
  std::vector<fs::path> paths;  // the trials with a result, in plan order
  for (const TrialOutcome& outcome : state.outcomes) {
    if (outcome.result_file.empty()) continue;
    paths.push_back(state.dir / outcome.result_file);
    ++out.trainings;
    out.complete += outcome.status == TrialOutcome::Status::complete;
    out.pruned += outcome.status == TrialOutcome::Status::pruned;
  }
  std::vector<ReadOutcome<RunRecord>> records = read_results(paths);
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const RunRecord r = std::move(records[k]).get();
    out.epochs += r.training.history.size();
    out.sources.push_back(paths[k]);
    out.configs.push_back(r.resolved_yaml);
  }
  const PointStats& best = state.summary.points.front();  // ranked: complete trials only
  out.chosen = point_text(state.plan.keys, best.values);
  out.chosen_repeats = best.complete;
  out.validation_mse = metric_or_nan(best.mean, kValidation);
  out.test_mse = metric_or_nan(best.mean, kTest);
  return out;
}

void print_table2_search(const StepErrorStudy& s, TableFormat format, std::ostream& out) {
  if (!s.search || !s.repeats) return;
  const SearchedSpace& grid = s.search->grid;
  const SearchedSpace& model = s.search->model;
  TypedTable t;
  t.columns = {label_column("search", "method"),
               label_column("space", "space"),
               pair_column("trainings (complete/run)", "complete", "trainings"),
               number_column("pruned", "pruned"),
               number_column("epochs trained", "epochs"),
               label_column("chosen on validation", "chosen"),
               number_column("validation MSE", "validation_mse"),
               number_column("test MSE (after the choice)", "test_mse")};
  for (const SearchedSpace* sp : {&grid, &model}) {
    t.rows.push_back(
        {source_cell(sp->method + (sp->pruner.empty() || sp->pruner == "none"
                                       ? std::string()
                                       : " + " + sp->pruner + " pruning")),
         sp->space,
         pair_cell(static_cast<double>(sp->complete), static_cast<double>(sp->trainings),
                   std::to_string(sp->complete) + "/" + std::to_string(sp->trainings)),
         number_cell(static_cast<double>(sp->pruned), std::to_string(sp->pruned)),
         number_cell(static_cast<double>(sp->epochs), std::to_string(sp->epochs)), sp->chosen,
         number_cell(sp->validation_mse, fixed_or_dash(sp->validation_mse, kTable2MseDecimals)),
         number_cell(sp->test_mse, fixed_or_dash(sp->test_mse, kTable2MseDecimals))});
  }
  print_table_title(out, format,
                    "Seed 000 Table 2's search (ours, " + s.repeats->variant +
                        "): the grid over p against " + model.method +
                        " over p x learning rate x momentum, MSE in z-score units");
  t.print(out, format);
  std::vector<std::string> notes = {
      "Both choose their point on the validation MSE (each sweep's objective, the lowest mean "
      "over the point's complete trainings); the test MSE of that point is reported after the "
      "choice and used for nothing.",
      "Grid: " + grid.file.filename().string() + ", every value with its seeds (the chosen " +
          "point's numbers are the mean over its " + std::to_string(grid.chosen_repeats) +
          " seeds), learning rate and momentum at the variant's settings. " + model.method + ": " +
          model.file.filename().string() + ", one training per sampled point (the " +
          "chosen point's numbers are one training's), pruned trainings kept but never " +
          "ranked; the two do not search the same space, so the table shows what each " +
          "search finds for its cost, not a controlled comparison.",
      "Grid " + ran_with(s.profile, grid.configs, step_error_settings_keys()) + ".",
      model.method + " " + ran_with(s.profile, model.configs, step_error_settings_keys()) + "."};
  print_table_notes(out, format, notes);
  std::vector<fs::path> read = grid.sources;
  read.insert(read.end(), model.sources.begin(), model.sources.end());
  print_table_sources(out, format, read);
}

}  // namespace cnclab
