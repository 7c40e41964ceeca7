#include "cnclab/studies/step_error/step_error_spread_table.hpp"

#include <cmath>
#include <cstdio>

#include "cnclab/report/run_settings.hpp"
#include "cnclab/report/statistics.hpp"
#include "cnclab/report/typed_table.hpp"
#include "cnclab/studies/step_error/step_error_measures.hpp"
#include "cnclab/studies/step_error/step_error_seed_notes.hpp"
#include "cnclab/studies/step_error/step_error_table_parts.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// A quantity of the table: its figure (run_figures name), how it is shown
// and where the paper gives it.
struct SpreadQuantity {
  std::string label, key, figure;
  int decimals = 3;
};

const SpreadQuantity kShareBelow05{"|e| < 0.5 µm (%)", "share_abs_below_0.5um_percent",
                                   "share_abs_below_0.5um", 2};
const SpreadQuantity kShareBelow1{"|e| < 1 µm (%)", "share_abs_below_1um_percent",
                                  "share_abs_below_1um", 2};
const SpreadQuantity kMaxAbs{"max |e| (µm)", "max_abs_um", "max_abs_um", 3};
const SpreadQuantity kMeanAbs{"mean |e| (µm)", "mean_abs_um", "mean_abs_um", 3};

TableCell spread_value_cell(double v, int decimals) {
  return std::isnan(v) ? missing_cell("-") : number_cell(v, fixed_or_dash(v, decimals));
}

// mean ± std over the point's seeds ("-" without a point or seed).
TableCell spread_seeds_cell(const RepeatedPoint* point, const SpreadQuantity& q) {
  if (!point || point->sample(q.figure).empty()) return missing_cell("-");
  const SampleSummary s = summarize(point->sample(q.figure));
  const std::string text =
      s.n < 2 ? fixed_or_dash(s.mean, q.decimals)
              : fixed_or_dash(s.mean, q.decimals) + " ± " + fixed_or_dash(s.std, q.decimals);
  return mean_std_cell(s.mean, s.std, text);
}

TableCell spread_count_cell(const RepeatedPoint* point) {
  return point ? number_cell(
                     static_cast<double>(point->runs.size()),
                     std::to_string(point->runs.size()) + "/" + std::to_string(point->planned))
               : missing_cell("-");
}

SeedSample spread_sample(const RepeatedPoint& point, const std::string& label,
                         const std::string& figure) {
  return {label, point.sample(figure)};
}

}  // namespace

std::vector<std::string> normaliser_seed_notes(const StepErrorRepeats& r) {
  std::vector<std::string> notes;
  for (const auto* sweep : {&r.surface2_ft15, &r.surface3_ft15}) {
    const RepeatedPoint* refit = sweep->find("refit");
    const RepeatedPoint* keep = sweep->find("keep");
    if (!refit || !keep) continue;
    const std::string surface = sweep == &r.surface2_ft15 ? "2" : "3";
    notes.push_back(seed_difference_sentence(
        "ours, " + r.variant + ", surface " + surface + " at 15 %, mean |e| (µm) over seeds",
        spread_sample(*refit, "refit", kMeanAbs.figure),
        spread_sample(*keep, "keep", kMeanAbs.figure), kMeanAbs.decimals));
  }
  return notes;
}

void print_step_error_spread(const StepErrorStudy& s, TableFormat format, std::ostream& out) {
  if (!s.repeats) return;
  const StepErrorRepeats& r = *s.repeats;
  const StudyVariant* variant = nullptr;
  for (const auto& v : s.manifest.variants) {
    if (v.name == r.variant) variant = &v;
  }
  const std::string ours = "ours, " + r.variant;
  TypedTable t;
  t.columns = {label_column("Headline row", "row"),
               label_column("", "quantity"),
               number_column("paper", "paper"),
               number_column(ours + " (one run)", "one_run"),
               mean_std_column(ours + ", mean ± std over seeds", "seeds", ""),
               number_column("seeds", "seeds")};
  const auto row = [&](const TableCell& what, const SpreadQuantity& q, double paper,
                       const StepErrorRun* one, const RepeatedPoint* point) {
    const bool ran = one && one->failure.empty();
    t.rows.push_back({what, label_cell(q.label, q.key), spread_value_cell(paper, q.decimals),
                      ran ? spread_value_cell(run_figures(*one).at(q.figure), q.decimals)
                          : missing_cell(one ? "diverged" : "-"),
                      spread_seeds_cell(point, q), spread_count_cell(point)});
  };
  const RepeatedPoint* s1 = r.surface1.find(kNoDropout);
  const StepErrorRun* s1_run = variant ? &s.at(variant->surface1_no_dropout) : nullptr;
  const TableCell s1_label = label_cell("Surface 1, no dropout", "surface1");
  row(s1_label, kShareBelow05, s.ref.table3_share_below_0_5um, s1_run, s1);
  row(s1_label, kMaxAbs, s.ref.table3_max_abs_um, s1_run, s1);
  row(s1_label, kMeanAbs, NAN, s1_run, s1);
  std::vector<fs::path> read = {s.reference_file};
  for (const auto* sweep : {&r.surface2_ft15, &r.surface3_ft15}) {
    const bool two = sweep == &r.surface2_ft15;
    const PaperSurfaceText& paper = two ? s.ref.surface2 : s.ref.surface3;
    for (const auto& n : s.manifest.normaliser) {
      const RepeatedPoint* point = sweep->find(n.name);
      const StepErrorRun* one = &s.at(two ? n.surface2 : n.surface3);
      const std::string surface = two ? "2" : "3";
      const TableCell label = label_cell("Surface " + surface + ", 15 %, " + n.name,
                                         "surface" + surface + "_ft15_" + n.name);
      row(label, kShareBelow1, paper.share_below_1um_at_15, one, point);
      row(label, kMaxAbs, paper.max_abs_at_15, one, point);
      row(label, kMeanAbs, paper.mean_abs_at_15, one, point);
    }
  }
  print_table_title(out, format,
                    "Seed-to-seed spread of the headline rows (" + ours +
                        "): the paper's single number, our run of Tables 3-7, mean ± std over "
                        "seeds");
  t.print(out, format);
  std::vector<std::string> notes = {
      "mean ± std (n − 1) over the complete trials of the seed sweeps (seeds: complete/planned): "
      "repeat 0 at the experiment's seed, the others at seeds derived from it (sweep repeats). "
      "Surface 1: a seed draws the 70/30 split, the initial weights and the "
      "mini-batch order; the 15 % rows: the fine-tuning share and the order, from the one "
      "upstream network. The paper reports one run.",
      "Differences are stated below only where Welch's test over the seeds gives p < 0.05."};
  std::vector<std::string> configs;
  for (const auto* sweep : {&r.surface1, &r.surface2_ft15, &r.surface3_ft15}) {
    configs.insert(configs.end(), sweep->configs.begin(), sweep->configs.end());
  }
  notes.push_back("The trials " + ran_with(s.profile, configs, step_error_settings_keys()) + ".");
  for (auto& n : normaliser_seed_notes(r)) notes.push_back(n);
  print_table_notes(out, format, notes);
  for (const auto* sweep : {&r.surface1, &r.surface2_ft15, &r.surface3_ft15}) {
    read.insert(read.end(), sweep->sources.begin(), sweep->sources.end());
  }
  print_table_sources(out, format, read);
}

}  // namespace cnclab
