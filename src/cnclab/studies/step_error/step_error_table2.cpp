#include "cnclab/studies/step_error/step_error_table2.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "cnclab/core/format.hpp"
#include "cnclab/report/run_settings.hpp"
#include "cnclab/report/statistics.hpp"
#include "cnclab/report/typed_table.hpp"
#include "cnclab/studies/step_error/step_error_seed_notes.hpp"
#include "cnclab/studies/step_error/step_error_table_parts.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr double kNoDropout = 1.0;  // the surface-1 point of the keep-probability sweep
// No dropout reaches 0.002 in z-score units, whose spread needs a fourth decimal.
constexpr int kMseDecimals = 4;
constexpr const char* kDeterministic = "test_mse_deterministic";
constexpr const char* kMc = "test_mse_mc";

std::string seeds_fixed(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", kMseDecimals, v);
  return buf;
}

// mean ± std of `figure` over the point's seeds ("-" without a value).
TableCell seeds_cell(const RepeatedPoint* point, const std::string& figure) {
  if (!point || point->sample(figure).empty()) return missing_cell("-");
  const SampleSummary s = summarize(point->sample(figure));
  return mean_std_cell(
      s.mean, s.std,
      s.n < 2 ? seeds_fixed(s.mean) : seeds_fixed(s.mean) + " ± " + seeds_fixed(s.std));
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
  bool mc_absent = false;
  for (const auto& v : s.manifest.variants) {
    std::vector<TableCell> test = {source_cell(ours(v)),
                                   label_cell("test MSE, deterministic", "test_mse")};
    std::vector<TableCell> mc = {source_cell(ours(v)),
                                 label_cell("test MSE, MC dropout", "test_mse_mc")};
    std::vector<TableCell> train = {source_cell(ours(v)),
                                    label_cell("training loss, last epoch", "train_loss")};
    double best = NAN, best_p = NAN, best_mc = NAN, best_p_mc = NAN;
    for (double p : s.ref.table2_p) {
      const StepErrorRun* run = s.find(v.table2, p);
      if (run) read.push_back(run);
      if (run && !run->failure.empty()) {
        for (auto* row : {&test, &mc, &train}) row->push_back(missing_cell("diverged"));
        continue;
      }
      const double mse = run ? inference_test_mse(*run, DropoutInference::deterministic) : NAN;
      const double mse_mc = run ? inference_test_mse(*run, DropoutInference::mc) : NAN;
      mc_absent = mc_absent || (run && std::isnan(mse_mc));
      const auto& h = run ? run->record.training.history : std::vector<EpochRecord>{};
      test.push_back(number_cell(mse, table_number(mse, 3)));
      mc.push_back(number_cell(mse_mc, table_number(mse_mc, 3)));
      train.push_back(h.empty()
                          ? missing_cell("-")
                          : number_cell(h.back().train_loss, table_number(h.back().train_loss, 3)));
      for (auto [value, least, at] :
           {std::tuple{mse, &best, &best_p}, std::tuple{mse_mc, &best_mc, &best_p_mc}}) {
        if (!std::isnan(value) && !(value >= *least)) {
          *least = value;
          *at = p;
        }
      }
    }
    t.rows.push_back(test);
    t.rows.push_back(mc);
    t.rows.push_back(train);
    notes.push_back(ours(v) + ": the run shown has its lowest test MSE at p = " +
                    table_number(best_p) + ", under MC dropout at p = " + table_number(best_p_mc) +
                    " (paper: minimum at p = " + table_number(paper_best_p) + ")" +
                    (s.repeats && s.repeats->variant == v.name
                         ? "; over seeds: the next table."
                         : "; one run per p, no seed repeats: not a finding."));
  }
  print_table_title(
      out, format, "Seed 000 Table 2: dropout keep probability p and MSE (surface 1, 70/30 split)");
  t.print(out, format);
  notes.push_back(
      "MSE in the z-score units of the targets (Eq. 7, fitted on the training split). The paper "
      "does not say whether its MSE is the training loss or a test error, nor in which units; "
      "both of ours are shown. Training loss is with dropout active (mean over the epoch).");
  notes.push_back(
      "Test MSE: the network evaluated deterministically (every unit kept, r = 1); MC dropout: "
      "the same trained network, per test sample the mean of model.dropout.mc_samples passes "
      "with new masks (Gal & Ghahramani 2016). Seed 000 does not say which it used.");
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

std::vector<std::string> table2_seed_notes(const StepErrorRepeats& r, const std::string& figure,
                                           const std::string& evaluation) {
  std::vector<SeedSample> by_p;
  for (const auto& point : r.surface1.points) {
    if (point.number() != kNoDropout) by_p.push_back({"p = " + point.value, point.sample(figure)});
  }
  std::vector<std::string> notes;
  const std::string what = "ours, " + r.variant + ", " + evaluation + ", test MSE over seeds";
  const std::string lowest = lowest_mean_sentence(what, by_p, kMseDecimals);
  if (!lowest.empty()) notes.push_back(lowest);
  const RepeatedPoint* none = r.surface1.find(kNoDropout);
  const SeedSample* best = nullptr;
  for (const auto& s : by_p) {
    if (s.values.size() >= 2 &&
        (!best || summarize(s.values).mean < summarize(best->values).mean)) {
      best = &s;
    }
  }
  if (none && best) {
    notes.push_back(seed_difference_sentence(
        "ours, " + r.variant + ", " + evaluation + ", no dropout against the best p (test MSE)",
        {"keep 1.0", none->sample(figure)}, *best, kMseDecimals));
  }
  return notes;
}

void print_table2_over_seeds(const StepErrorStudy& s, TableFormat format, std::ostream& out) {
  if (!s.repeats) return;
  const StepErrorRepeats& r = *s.repeats;
  const RepeatedSweep& sweep = r.surface1;
  const std::string passes = mc_passes(sweep);
  TypedTable t;
  t.columns = {number_column("p (keep probability)", "p"), number_column("paper MSE", "paper_mse"),
               mean_std_column("deterministic", "test_mse_deterministic", ""),
               mean_std_column("MC dropout (" + passes + " masks)", "test_mse_mc", ""),
               pair_column("seeds", "complete", "planned")};
  std::vector<double> ps = s.ref.table2_p;
  ps.push_back(kNoDropout);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double p = ps[i];
    const double paper = i < s.ref.table2_mse.size() ? s.ref.table2_mse[i] : NAN;
    const RepeatedPoint* point = sweep.find(p);
    t.rows.push_back(
        {number_cell(p, p == kNoDropout ? "1.0 (no dropout)" : table_number(p)),
         std::isnan(paper) ? missing_cell("-") : number_cell(paper, table_number(paper)),
         seeds_cell(point, kDeterministic), seeds_cell(point, kMc), planned_cell(point)});
  }
  print_table_title(out, format,
                    "Seed 000 Table 2 over seeds (ours, " + r.variant +
                        "): test MSE (z-score units), mean ± std, each network evaluated "
                        "deterministically and by MC dropout");
  t.print(out, format);
  std::vector<std::string> notes = {
      "One training per seed and p, evaluated both ways: deterministic (one pass with every unit "
      "kept, r = 1) and MC dropout (per test sample the mean of " +
          passes +
          " passes with new masks r ~ Bernoulli(p), from the run's own random stream; Gal & "
          "Ghahramani 2016). Seed 000 does not say which it used. With no dropout (1.0) the two "
          "are the same network.",
      "Variant " + r.variant + " " +
          ran_with(s.profile, sweep.configs, step_error_settings_keys()) +
          "; seeds: the sweep's repeats (sweep repeats)."};
  for (auto& n : table2_seed_notes(r, kDeterministic, "deterministic")) notes.push_back(n);
  for (auto& n : table2_seed_notes(r, kMc, "MC dropout")) notes.push_back(n);
  bool absent = false;
  for (const auto& point : sweep.points) {
    absent = absent || point.sample(kMc).size() < point.runs.size();
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
