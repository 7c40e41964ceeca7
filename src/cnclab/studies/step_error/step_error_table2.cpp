#include "cnclab/studies/step_error/step_error_table2.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cnclab/core/format.hpp"
#include "cnclab/report/run_settings.hpp"
#include "cnclab/report/statistics.hpp"
#include "cnclab/report/typed_table.hpp"
#include "cnclab/studies/step_error/step_error_measures.hpp"
#include "cnclab/studies/step_error/step_error_seed_notes.hpp"
#include "cnclab/studies/step_error/step_error_table_parts.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// No dropout reaches 0.002 in z-score units, whose spread needs a fourth decimal.
constexpr int kMseDecimals = 4;

// Table 2's two evaluations of each network: how the notes name it, and the
// suffix of its figures (run_figures).
struct Table2Evaluation {
  const char* name;
  const char* suffix;
};
constexpr Table2Evaluation kTable2Deterministic{"deterministic", "_deterministic"};
constexpr Table2Evaluation kTable2Mc{"MC dropout", "_mc"};

// mean ± std of `figure` over the point's seeds ("-" without a value).
TableCell seeds_cell(const RepeatedPoint* point, const std::string& figure) {
  if (!point || point->sample(figure).empty()) return missing_cell("-");
  const SampleSummary s = summarize(point->sample(figure));
  return mean_std_cell(
      s.mean, s.std,
      s.n < 2 ? fixed_decimals(s.mean, kMseDecimals)
              : fixed_decimals(s.mean, kMseDecimals) + " ± " + fixed_decimals(s.std, kMseDecimals));
}

TableCell planned_cell(const RepeatedPoint* point) {
  return point ? pair_cell(
                     static_cast<double>(point->runs.size()), static_cast<double>(point->planned),
                     std::to_string(point->runs.size()) + "/" + std::to_string(point->planned))
               : missing_cell("-");
}

// The Monte-Carlo passes of the sweep's trials ("100"; several: "50 or 100").
std::string mc_passes(const RepeatedSweep& sweep) {
  std::vector<double> values;
  for (const auto& point : sweep.points) {
    for (double v : point.sample("mc_samples")) {
      if (std::find(values.begin(), values.end(), v) == values.end()) values.push_back(v);
    }
  }
  std::string out;
  for (double v : values) out += (out.empty() ? "" : " or ") + table_number(v);
  return out.empty() ? "-" : out;
}

// "60/10/30" (train/validation/test, % of the samples); "70/30" without validation.
std::string split_text(const RunRecord& r) {
  const double n =
      static_cast<double>(r.split.train.size() + r.split.validation.size() + r.split.test.size());
  std::string out;
  for (const auto* part : {&r.split.train, &r.split.validation, &r.split.test}) {
    if (part == &r.split.validation && part->empty()) continue;
    char buf[16];
    std::snprintf(buf, sizeof buf, "%s%.0f", out.empty() ? "" : "/",
                  100.0 * static_cast<double>(part->size()) / n);
    out += buf;
  }
  return out;
}

// The splits of Table 2's runs, "60/10/30" (several: "60/10/30 and 70/30").
std::string table2_splits(const std::vector<const StepErrorRun*>& runs) {
  std::vector<std::string> texts;
  for (const StepErrorRun* r : runs) {
    const std::string t = split_text(r->record);
    if (std::find(texts.begin(), texts.end(), t) == texts.end()) texts.push_back(t);
  }
  std::string out;
  for (const auto& t : texts) {
    if (!out.empty()) out += " and ";
    out += t;
  }
  return out.empty() ? "-" : out;
}

}  // namespace

void print_table2(const StepErrorStudy& s, TableFormat format, std::ostream& out) {
  TypedTable t;
  t.columns = {label_column("p (keep probability)", "source"), label_column("", "quantity")};
  for (double p : s.ref.table2_p) {
    std::string name = "p_";  // appended: see bin_columns
    name += shortest_double(p);
    t.columns.push_back(number_column(table_number(p), name));
  }
  std::vector<TableCell> paper = {"paper", label_cell("MSE", "mse")};
  for (double m : s.ref.table2_mse) paper.push_back(number_cell(m, table_number(m)));
  t.rows.push_back(paper);
  std::vector<std::string> notes;
  std::vector<const StepErrorRun*> read;
  // The paper's minimum, from its own row.
  const auto paper_min = std::min_element(s.ref.table2_mse.begin(), s.ref.table2_mse.end());
  const double paper_best_p =
      paper_min == s.ref.table2_mse.end()
          ? NAN
          : s.ref.table2_p[static_cast<std::size_t>(paper_min - s.ref.table2_mse.begin())];
  bool mc_absent = false, validation = false;
  const auto cell = [](double v) { return number_cell(v, table_number(v, 3)); };
  for (const auto& v : s.manifest.variants) {
    std::vector<TableCell> val = {source_cell(ours(v)),
                                  label_cell("validation MSE, deterministic", "validation_mse")};
    std::vector<TableCell> test = {source_cell(ours(v)),
                                   label_cell("test MSE, deterministic", "test_mse")};
    std::vector<TableCell> mc = {source_cell(ours(v)),
                                 label_cell("test MSE, MC dropout", "test_mse_mc")};
    std::vector<TableCell> train = {source_cell(ours(v)),
                                    label_cell("training loss, last epoch", "train_loss")};
    for (double p : s.ref.table2_p) {
      const StepErrorRun* run = s.find(v.table2, p);
      if (run) read.push_back(run);
      if (run && !run->failure.empty()) {
        for (auto* row : {&val, &test, &mc, &train}) row->push_back(missing_cell("diverged"));
        continue;
      }
      const double mse_mc = run ? inference_test_mse(*run, DropoutInference::mc) : NAN;
      mc_absent = mc_absent || (run && std::isnan(mse_mc));
      validation = validation || (run && !run->record.split.validation.empty());
      const auto& h = run ? run->record.training.history : std::vector<EpochRecord>{};
      val.push_back(
          cell(run ? inference_validation_mse(*run, DropoutInference::deterministic) : NAN));
      test.push_back(cell(run ? inference_test_mse(*run, DropoutInference::deterministic) : NAN));
      mc.push_back(cell(mse_mc));
      train.push_back(h.empty() ? missing_cell("-") : cell(h.back().train_loss));
    }
    for (auto* row : {&val, &test, &mc, &train}) t.rows.push_back(*row);
    const Table2Choice choice = table2_choice(s, v, DropoutInference::deterministic);
    const Table2Choice choice_mc = table2_choice(s, v, DropoutInference::mc);
    notes.push_back(
        ours(v) + ": chosen on validation, p = " + table_number(choice.on_validation) +
        " (the lowest validation MSE of the run shown, deterministic evaluation); on test "
        "instead (Table 2's own reading, which chooses on the data it reports; shown beside, not "
        "used): p = " +
        table_number(choice.on_test) +
        (choice.on_validation == choice.on_test ? ", the same" : ", another") +
        "; under MC dropout, chosen on its own validation MSE (stored in the result files), p = " +
        table_number(choice_mc.on_validation) + ", on test p = " + table_number(choice_mc.on_test) +
        "; paper: minimum at p = " + table_number(paper_best_p) +
        (s.repeats && s.repeats->variant == v.name
             ? ". Over seeds: the next table."
             : ". One run per p, no seed repeats: not a finding."));
  }
  print_table_title(out, format,
                    "Seed 000 Table 2: dropout keep probability p and MSE (surface 1, " +
                        table2_splits(read) + " split)");
  t.print(out, format);
  notes.push_back(
      "MSE in the z-score units of the targets (Eq. 7, fitted on the training split). The paper "
      "does not say whether its MSE is the training loss or a test error, nor in which units; "
      "ours are shown on each. Training loss is with dropout active (mean over the epoch).");
  notes.push_back(
      validation
          ? "Split: the paper's 70/30 has no validation part, so Table 2's runs hold 10 % of the "
            "samples out of its 70 % training part to choose p on (60/10/30; the 30 % test "
            "samples are those of surface 1's 70/30 split): p is chosen on validation, test is "
            "reported after."
          : "Split: Table 2's runs have no validation part, so no p is chosen ('-'); the lowest "
            "test MSE is shown, not used.");
  notes.push_back(
      "Deterministic: the network evaluated with every unit kept (r = 1); MC dropout: the same "
      "trained network, per sample the mean of model.dropout.mc_samples passes with new masks "
      "(Gal & Ghahramani 2016). Seed 000 does not say which it used.");
  if (mc_absent) {
    notes.push_back(
        "MC dropout '-': a result written before cnclab stored the MC evaluation; `cnclab run` "
        "of its experiment file" +
        (s.profile.empty() ? std::string() : " with --profile " + s.profile) + " writes it anew.");
  }
  notes.push_back(
      "'diverged': training with the paper's settings (N(0, 1) weights, per-sample SGDM) ended "
      "with a non-finite loss at that p; its result file says when.");
  for (auto& n :
       variant_settings_notes(s, [&](const StudyVariant& v) { return study_runs(s, v.table2); })) {
    notes.push_back(n);
  }
  print_table_notes(out, format, notes);
  print_sources(out, format, s.reference_file, read);
}

std::vector<std::string> table2_seed_notes(const StepErrorRepeats& r, const std::string& suffix,
                                           const std::string& evaluation) {
  const std::string validation_figure = "validation_mse" + suffix;
  const std::string test_figure = "test_mse" + suffix;
  // Table 2's keep probabilities (not 1.0, no dropout), by each split's MSE.
  std::vector<SeedSample> by_validation, by_test;
  for (const auto& point : r.table2.points) {
    if (point.number() == kNoDropout) continue;
    by_validation.push_back({"p = " + point.value, point.sample(validation_figure)});
    by_test.push_back({"p = " + point.value, point.sample(test_figure)});
  }
  const std::string ours = "ours, " + r.variant + ", " + evaluation;
  std::vector<std::string> notes;
  const std::string chosen_text = lowest_mean_sentence(
      ours + ", validation MSE over seeds (the choice of p)", by_validation, kMseDecimals);
  if (!chosen_text.empty()) notes.push_back(chosen_text);
  const RepeatedPoint* chosen = table2_choice_over_seeds(r.table2, validation_figure);
  const RepeatedPoint* on_test = table2_choice_over_seeds(r.table2, test_figure);
  const RepeatedPoint* none = r.table2.find(kNoDropout);
  if (!chosen) {
    notes.push_back(ours + ": no p has a validation MSE over 2 seeds or more, so none is chosen.");
  } else {
    notes.push_back(ours + ", the chosen p = " + chosen->value +
                    ", test MSE over seeds (reported after the choice): " +
                    seed_mean_std_text(summarize(chosen->sample(test_figure)), kMseDecimals) + ".");
  }
  if (chosen && none) {
    const std::string p = "p = " + chosen->value;
    notes.push_back(seed_difference_sentence(
        ours + ", no dropout against the chosen p (validation MSE, the choice)",
        {"keep 1.0", none->sample(validation_figure)}, {p, chosen->sample(validation_figure)},
        kMseDecimals));
    notes.push_back(seed_difference_sentence(ours + ", the same on test (reported after)",
                                             {"keep 1.0", none->sample(test_figure)},
                                             {p, chosen->sample(test_figure)}, kMseDecimals));
  }
  // Beside it, the choice the paper's Table 2 invites (it reports one MSE
  // per p and picks the lowest): on test, which selects on the data it
  // reports. Shown, not used.
  const std::string test_text = lowest_mean_sentence(
      ours +
          ", on test instead (Table 2's own reading: choosing on the data it reports; shown "
          "beside, not used)",
      by_test, kMseDecimals);
  if (!test_text.empty()) notes.push_back(test_text);
  if (chosen && on_test) {
    notes.push_back(ours + ": the lowest mean on validation (p = " + chosen->value +
                    ") and on test (p = " + on_test->value + ") " +
                    (chosen == on_test ? "agree." : "differ; the validation choice stands."));
  }
  return notes;
}

void print_table2_over_seeds(const StepErrorStudy& s, TableFormat format, std::ostream& out) {
  if (!s.repeats) return;
  const StepErrorRepeats& r = *s.repeats;
  const RepeatedSweep& sweep = r.table2;
  const std::string passes = mc_passes(sweep);
  TypedTable t;
  t.columns = {number_column("p (keep probability)", "p"), number_column("paper MSE", "paper_mse")};
  for (const Table2Evaluation& e : {kTable2Deterministic, kTable2Mc}) {
    const std::string name =
        std::string(e.suffix) == kTable2Mc.suffix ? "MC dropout (" + passes + " masks)" : e.name;
    t.columns.push_back(
        mean_std_column("validation, " + name, std::string("validation_mse") + e.suffix, ""));
    t.columns.push_back(mean_std_column("test, " + name, std::string("test_mse") + e.suffix, ""));
  }
  t.columns.push_back(pair_column("seeds", "complete", "planned"));
  std::vector<double> ps = s.ref.table2_p;
  ps.push_back(kNoDropout);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double p = ps[i];
    const double paper = i < s.ref.table2_mse.size() ? s.ref.table2_mse[i] : NAN;
    const RepeatedPoint* point = sweep.find(p);
    std::vector<TableCell> row = {
        number_cell(p, p == kNoDropout ? "1.0 (no dropout)" : table_number(p)),
        std::isnan(paper) ? missing_cell("-") : number_cell(paper, table_number(paper))};
    for (const Table2Evaluation& e : {kTable2Deterministic, kTable2Mc}) {
      row.push_back(seeds_cell(point, std::string("validation_mse") + e.suffix));
      row.push_back(seeds_cell(point, std::string("test_mse") + e.suffix));
    }
    row.push_back(planned_cell(point));
    t.rows.push_back(row);
  }
  print_table_title(out, format,
                    "Seed 000 Table 2 over seeds (ours, " + r.variant +
                        "): validation and test MSE (z-score units), mean ± std, each network "
                        "evaluated deterministically and by MC dropout");
  t.print(out, format);
  std::vector<std::string> notes = {
      "One training per seed and p, evaluated both ways: deterministic (one pass with every unit "
      "kept, r = 1) and MC dropout (per sample the mean of " +
          passes +
          " passes with new masks r ~ Bernoulli(p), from the run's own random stream; Gal & "
          "Ghahramani 2016). Seed 000 does not say which it used. With no dropout (1.0) the two "
          "are the same network.",
      "Each evaluation chooses p on its own lowest mean validation MSE (the validation part "
      "held out of the training part); its test MSE is reported after the choice. A seed draws "
      "the split, the initial weights and the mini-batch order.",
      "Variant " + r.variant + " " +
          ran_with(s.profile, sweep.configs, step_error_settings_keys()) +
          "; seeds: the sweep's repeats (sweep repeats).",
      "Differences are stated below only where Welch's test over the seeds gives p < 0.05."};
  for (const Table2Evaluation& e : {kTable2Deterministic, kTable2Mc}) {
    for (auto& n : table2_seed_notes(r, e.suffix, e.name)) notes.push_back(n);
  }
  bool absent = false;
  const std::string mc_test = std::string("test_mse") + kTable2Mc.suffix;
  for (const auto& point : sweep.points) {
    absent = absent || point.sample(mc_test).size() < point.runs.size();
  }
  if (absent) {
    notes.push_back(
        "MC dropout '-' or fewer seeds: results written before cnclab stored the MC evaluation "
        "beside the deterministic one; `cnclab reproduce --force" +
        (s.profile.empty() ? std::string() : " --profile " + s.profile) + " " +
        sweep.file.string() + "` remakes them.");
  }
  print_table_notes(out, format, notes);
  std::vector<fs::path> read = {s.reference_file};
  read.insert(read.end(), sweep.sources.begin(), sweep.sources.end());
  print_table_sources(out, format, read);
}

}  // namespace cnclab
