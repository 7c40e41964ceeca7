#include "cnclab/studies/step_error/step_error_tables.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "cnclab/core/format.hpp"
#include "cnclab/report/run_settings.hpp"
#include "cnclab/report/typed_table.hpp"
#include "cnclab/studies/step_error/step_error_spread_table.hpp"
#include "cnclab/studies/step_error/step_error_study.hpp"
#include "cnclab/studies/step_error/step_error_table2.hpp"
#include "cnclab/studies/step_error/step_error_table8.hpp"
#include "cnclab/studies/step_error/step_error_table_parts.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr double kFineTuneReported = 15;  // Tables 6, 7 and the normaliser table: 15 %

using Run = StepErrorRun;
using Study = StepErrorStudy;

std::string um(double v) {
  return table_number(v, 3);
}

std::string integer(double v) {
  return std::isnan(v) ? "-" : std::to_string(static_cast<long long>(std::llround(v)));
}

// 5940 -> "5,940" (the papers' digit grouping).
std::string grouped(double v) {
  const std::string digits = integer(v);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && digits[i - 1] != '-' && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

// Typed cells (csv/json carry the number) with the texts above.
TableCell fixed_cell(double v) {
  return number_cell(v, fixed_or_dash(v, 2));
}
TableCell um_cell(double v) {
  return number_cell(v, um(v));
}
TableCell count_cell(std::size_t n) {
  return number_cell(static_cast<double>(n), std::to_string(n));
}
TableCell integer_cell(double v) {
  return number_cell(v, integer(v));
}

// The reference's sentences about one table ("Table 6: ...").
std::vector<std::string> checks_about(const Seed000Reference& ref, const std::string& table) {
  std::vector<std::string> out;
  for (const auto& c : ref.checks) {
    if (c.rfind(table + ":", 0) == 0 || c.rfind(table + " ", 0) == 0) {
      out.push_back("Paper check (results/reference): " + c);
    }
  }
  return out;
}

const std::string kSurfacesNote =
    "Our surfaces are our own bicubic NURBS designed to the paper's bounding boxes and "
    "step-error ranges (the paper's were not published; README, Step-error datasets), so our "
    "numbers compare with the paper's in kind and magnitude, not sample by sample.";

const std::string kBinsNote =
    "Bins are half-open [a, b): '< 0.1' is [0, 0.1), '0.1–0.2' is [0.1, 0.2); the last "
    "column counts everything at or above the paper's last edge (the paper's tables stop there).";

const std::string kRelativeNote =
    "Relative error = 100 |predicted − theoretical| / theoretical; near-zero theoretical step "
    "errors make it large, whatever the absolute error.";

// Bin rows "Number" and "Ratio (%)" for one source; `overflow` adds the
// count at or above the last edge.
void add_bin_rows(TypedTable& t, const std::string& source, const BinCounts& b, bool overflow) {
  std::vector<TableCell> count = {source_cell(source), label_cell("Number", "count")};
  std::vector<TableCell> ratio = {source_cell(source), label_cell("Ratio (%)", "percent")};
  for (std::size_t c : b.counts) {
    count.push_back(count_cell(c));
    ratio.push_back(fixed_cell(percent(c, b.total())));
  }
  if (overflow) {
    count.push_back(count_cell(b.above));
    ratio.push_back(fixed_cell(percent(b.above, b.total())));
  }
  t.rows.push_back(count);
  t.rows.push_back(ratio);
}

void add_paper_bin_rows(TypedTable& t, const PaperBins& p, bool overflow) {
  std::vector<TableCell> count = {"paper", label_cell("Number", "count")};
  std::vector<TableCell> ratio = {"paper", label_cell("Ratio (%)", "percent")};
  for (std::size_t k = 0; k < p.count.size(); ++k) {
    count.push_back(integer_cell(p.count[k]));
    ratio.push_back(fixed_cell(p.percent[k]));
  }
  if (overflow) {
    count.push_back(missing_cell("-"));
    ratio.push_back(missing_cell("-"));
  }
  t.rows.push_back(count);
  t.rows.push_back(ratio);
}

// A relative-error table needs its last edge infinite: the bins then cover
// everything ("> 20 %"), the rare +inf (theoretical value 0) included.
BinCounts relative_bins(const ErrorFigures& f, const std::vector<double>& edges) {
  BinCounts b = bin_counts(f.rel_percent, edges);
  if (std::isinf(edges.back())) {
    b.counts.back() += b.above;
    b.above = 0;
  }
  return b;
}

// A pair of bin tables (absolute, relative) for `sources` (label, run).
void print_bin_tables(std::ostream& out, TableFormat format, const std::string& table,
                      const std::string& what, const PaperBinTable& paper,
                      const fs::path& reference,
                      const std::vector<std::pair<std::string, const Run*>>& sources,
                      std::vector<std::string> notes) {
  // Rows are quantities (count, percent): the unit of a bin column is its edges'.
  TypedTable a;
  a.columns = {label_column("(a) Absolute error (µm)", "source"), label_column("", "quantity")};
  for (auto& c : bin_columns(paper.absolute_um.edges, "um", "", true)) a.columns.push_back(c);
  add_paper_bin_rows(a, paper.absolute_um, true);
  for (const auto& [label, run] : sources) {
    add_bin_rows(a, label, bin_counts(run->figures.abs_um, paper.absolute_um.edges), true);
  }
  TypedTable r;
  const bool overflow = !std::isinf(paper.relative_percent.edges.back());
  r.columns = {label_column("(b) Relative error", "source"), label_column("", "quantity")};
  for (auto& c : bin_columns(paper.relative_percent.edges, "percent", "%", overflow)) {
    r.columns.push_back(c);
  }
  add_paper_bin_rows(r, paper.relative_percent, overflow);
  for (const auto& [label, run] : sources) {
    add_bin_rows(r, label, relative_bins(run->figures, paper.relative_percent.edges), overflow);
  }
  print_table_title(out, format, table + " (a): " + what + ", absolute error");
  a.print(out, format);
  print_table_title(out, format, table + " (b): " + what + ", relative error");
  r.print(out, format);
  notes.push_back(kBinsNote);
  notes.push_back(kRelativeNote);
  print_table_notes(out, format, notes);
  std::vector<const Run*> runs;
  for (const auto& [label, run] : sources) runs.push_back(run);
  print_sources(out, format, reference, runs);
}

// The text's share of relative errors above 10 % against Table 3's own counts
// (the bins from 10 % up over all bins), both from the reference file.
std::string paper_relative_above_10_note(const Seed000Reference& ref) {
  const PaperBins& b = ref.table3.relative_percent;
  std::size_t above = 0, total = 0;
  for (std::size_t k = 0; k < b.count.size(); ++k) {
    const auto n = static_cast<std::size_t>(std::llround(b.count[k]));
    total += n;
    if (b.edges[k] >= 10) above += n;
  }
  const std::string counted = fixed_or_dash(percent(above, total), 2);
  const std::string stated = fixed_or_dash(ref.table3_share_rel_above_10, 2);
  return "relative error > 10 %: the paper's " + stated + " % " +
         (counted == stated ? "agrees with" : "disagrees with") + " its own counts (" +
         grouped(static_cast<double>(above)) + " / " + grouped(static_cast<double>(total)) + " = " +
         counted + " %).";
}

void print_table3(const Study& s, TableFormat format, std::ostream& out) {
  std::vector<std::pair<std::string, const Run*>> sources;
  for (const auto& v : s.manifest.variants) {
    sources.push_back({ours(v), &s.at(v.surface1)});
    sources.push_back({ours(v) + ", no dropout", &s.at(v.surface1_no_dropout)});
  }
  print_bin_tables(out, format, "Seed 000 Table 3",
                   "prediction error of the surface-1 test samples", s.ref.table3, s.reference_file,
                   sources, checks_about(s.ref, "Table 3"));

  // Rows are quantities: csv/json carry each row's unit in its key.
  TypedTable t;
  t.columns = {label_column("Surface 1 test set", "quantity"), number_column("paper", "paper")};
  for (const auto& [label, run] : sources)
    t.columns.push_back(number_column(label, machine_name(label)));
  const auto row = [&](const TableCell& label, const TableCell& paper, auto&& value) {
    std::vector<TableCell> r = {label, paper};
    for (const auto& [l, run] : sources) r.push_back(value(*run));
    t.rows.push_back(r);
  };
  double paper_n = 0;
  for (double c : s.ref.table3.absolute_um.count) paper_n += c;
  row(label_cell("test samples", "test_samples"), integer_cell(paper_n),
      [](const Run& r) { return count_cell(r.figures.samples); });
  row(label_cell("max |e| (µm)", "max_abs_um"), um_cell(s.ref.table3_max_abs_um),
      [](const Run& r) { return um_cell(r.figures.max_abs); });
  row(label_cell("mean |e| (µm)", "mean_abs_um"), missing_cell("-"),
      [](const Run& r) { return um_cell(r.figures.mean_abs); });
  row(label_cell("|e| < 0.5 µm (%)", "share_abs_below_0.5um_percent"),
      fixed_cell(s.ref.table3_share_below_0_5um),
      [](const Run& r) { return fixed_cell(r.figures.share_abs_below(0.5)); });
  row(label_cell("relative error > 10 % (%)", "share_rel_above_10_percent"),
      fixed_cell(s.ref.table3_share_rel_above_10),
      [](const Run& r) { return fixed_cell(100.0 - r.figures.share_rel_below(10)); });
  row(label_cell("final training loss (z-score units)", "final_train_loss"),
      number_cell(s.ref.figure5_final_mse, table_number(s.ref.figure5_final_mse)),
      [](const Run& r) {
        const auto& h = r.record.training.history;
        return h.empty() ? missing_cell("-")
                         : number_cell(h.back().train_loss, table_number(h.back().train_loss, 3));
      });
  print_table_title(out, format, "Surface 1 in the text (below Fig. 6; Fig. 5's final MSE)");
  t.print(out, format);
  std::vector<std::string> notes = {
      "Targets on our surfaces (configs/studies/step_error_tables.yaml): >= 99.5 % of |e| < 0.5 µm "
      "and max |e| < 1 µm (paper: " +
          fixed_or_dash(s.ref.table3_share_below_0_5um, 2) + " %, " +
          table_number(s.ref.table3_max_abs_um) + " µm).",
      paper_relative_above_10_note(s.ref), kSurfacesNote};
  for (auto& n : variant_settings_notes(s, [&](const StudyVariant& v) {
         return std::vector<const Run*>{&s.at(v.surface1), &s.at(v.surface1_no_dropout)};
       })) {
    notes.push_back(n);
  }
  print_table_notes(out, format, notes);
  std::vector<const Run*> runs;
  for (const auto& [label, run] : sources) runs.push_back(run);
  print_sources(out, format, s.reference_file, runs);
}

// Tables 4 and 5 with the text's figures per fine-tune share.
void print_fine_tune_table(const Study& s, TableFormat format, std::ostream& out, int surface,
                           const PaperSurfaceText& paper) {
  const auto& shares = s.ref.fine_tune_percent;
  TypedTable t;
  t.columns = {label_column("Surface " + std::to_string(surface) + ", fine-tuned with", "quantity"),
               label_column("source", "source")};
  for (double p : shares) {
    std::string name = "fine_tune_";  // appended: see bin_columns
    name += shortest_double(p);
    t.columns.push_back(number_column(table_number(p) + " %", name, "percent"));
  }
  const auto files = [&](const StudyVariant& v) -> const std::map<double, fs::path>& {
    return surface == 2 ? v.surface2 : v.surface3;
  };
  // `paper_at(p)`: the paper's value at share p, NaN where it gives none.
  // Rows are quantities: csv/json carry the quantity (with its unit) on
  // every row, the continuation rows included.
  const auto metric = [&](const std::string& label, const std::string& key, auto&& paper_at,
                          auto&& ours_of) {
    std::vector<TableCell> r = {label_cell(label, key), "paper"};
    for (double p : shares) r.push_back(paper_at(p));
    t.rows.push_back(r);
    for (const auto& v : s.manifest.variants) {
      std::vector<TableCell> o = {label_cell("", key), source_cell(ours(v))};
      for (double p : shares) {
        const Run* run = s.find(files(v), p);
        o.push_back(run ? ours_of(*run) : missing_cell("-"));
      }
      t.rows.push_back(o);
    }
  };
  const auto at_0_15 = [](double p, double at0, double at15, auto&& fmt) -> TableCell {
    return p == 0 ? fmt(at0) : p == kFineTuneReported ? fmt(at15) : missing_cell("-");
  };
  metric(
      "test samples", "test_samples",
      [&](double p) {
        for (std::size_t i = 0; i < shares.size(); ++i) {
          if (shares[i] == p) return integer_cell(s.ref.test_samples[i]);
        }
        return missing_cell("-");
      },
      [](const Run& r) { return count_cell(r.figures.samples); });
  metric(
      "max |e| (µm)", "max_abs_um",
      [&](double p) { return at_0_15(p, paper.max_abs_at_0, paper.max_abs_at_15, um_cell); },
      [](const Run& r) { return um_cell(r.figures.max_abs); });
  metric(
      "|e| < 1 µm (%)", "share_abs_below_1um_percent",
      [&](double p) {
        return at_0_15(p, paper.share_below_1um_at_0, paper.share_below_1um_at_15, fixed_cell);
      },
      [](const Run& r) { return fixed_cell(r.figures.share_abs_below(1.0)); });
  metric(
      "mean |e| (µm)", "mean_abs_um",
      [&](double p) { return at_0_15(p, NAN, paper.mean_abs_at_15, um_cell); },
      [](const Run& r) { return um_cell(r.figures.mean_abs); });
  metric(
      "relative error < 10 % (%)", "share_rel_below_10_percent",
      [&](double p) { return at_0_15(p, NAN, paper.share_rel_below_10_at_15, fixed_cell); },
      [](const Run& r) { return fixed_cell(r.figures.share_rel_below(10)); });
  metric(
      "|e| < 0.4 µm (%)", "share_abs_below_0.4um_percent",
      [&](double p) { return at_0_15(p, NAN, paper.share_below_0_4um_at_15, fixed_cell); },
      [](const Run& r) { return fixed_cell(r.figures.share_abs_below(0.4)); });
  const int table = surface == 2 ? 4 : 5;
  print_table_title(out, format,
                    "Seed 000 Table " + std::to_string(table) + " (test sets) and the text of " +
                        "\"Predict step error values of Surface " + std::to_string(surface) + "\"");
  t.print(out, format);
  std::vector<std::string> notes = {
      "Each column fine-tunes the " +
          std::string(surface == 2 ? "surface-1 network"
                                   : "network trained on surface 1 and 15 % of surface 2") +
          " with that share of surface " + std::to_string(surface) +
          "'s samples and tests on the rest; '-': the paper gives no value there.",
      "Target: >= 99 % of |e| < 1 µm at 15 % (paper: " +
          fixed_or_dash(paper.share_below_1um_at_15, 2) + " %).",
      kSurfacesNote};
  if (surface == 2) {
    for (auto& c : checks_about(s.ref, "Table 6")) notes.push_back(c);
  } else {
    for (auto& c : checks_about(s.ref, "Table 7")) notes.push_back(c);
  }
  for (auto& c : checks_about(s.ref, "Tables 4 and 5")) notes.push_back(c);
  for (auto& n :
       variant_settings_notes(s, [&](const StudyVariant& v) { return study_runs(s, files(v)); })) {
    notes.push_back(n);
  }
  print_table_notes(out, format, notes);
  std::vector<const Run*> runs;
  for (const auto& v : s.manifest.variants) {
    for (double p : shares) {
      if (const Run* run = s.find(files(v), p)) runs.push_back(run);
    }
  }
  print_sources(out, format, s.reference_file, runs);
}

void print_bins_at_15(const Study& s, TableFormat format, std::ostream& out, int surface) {
  std::vector<std::pair<std::string, const Run*>> sources;
  for (const auto& v : s.manifest.variants) {
    if (const Run* r = s.find(surface == 2 ? v.surface2 : v.surface3, kFineTuneReported)) {
      sources.push_back({ours(v), r});
    }
  }
  const int table = surface == 2 ? 6 : 7;
  std::vector<std::string> notes = checks_about(s.ref, "Table " + std::to_string(table));
  for (auto& n : variant_settings_notes(s, [&](const StudyVariant& v) {
         std::vector<const Run*> runs;
         if (const Run* r = s.find(surface == 2 ? v.surface2 : v.surface3, kFineTuneReported)) {
           runs.push_back(r);
         }
         return runs;
       })) {
    notes.push_back(n);
  }
  print_bin_tables(out, format, "Seed 000 Table " + std::to_string(table),
                   "prediction error of the surface-" + std::to_string(surface) +
                       " test set at 15 % fine-tuning",
                   surface == 2 ? s.ref.table6 : s.ref.table7, s.reference_file, sources, notes);
}

void print_normaliser_table(const Study& s, TableFormat format, std::ostream& out) {
  TypedTable t;
  std::vector<const Run*> read;
  t.columns = {label_column("Normaliser at 15 %", "normaliser"),
               number_column("test samples", "test_samples"),
               number_column("max |e| (µm)", "max_abs", "um"),
               number_column("|e| < 1 µm (%)", "share_abs_below_1um", "percent"),
               number_column("mean |e| (µm)", "mean_abs", "um"),
               number_column("relative error < 10 % (%)", "share_rel_below_10", "percent")};
  for (const char* surface : {"surface2", "surface3"}) {
    for (const auto& n : s.manifest.normaliser) {
      const Run& r = s.at(std::string(surface) == "surface2" ? n.surface2 : n.surface3);
      read.push_back(&r);
      const std::string label =
          std::string(surface == std::string("surface2") ? "surface 2" : "surface 3") + ", " +
          n.name + (n.name == s.manifest.normaliser_default ? " (default)" : "");
      t.rows.push_back({label, count_cell(r.figures.samples), um_cell(r.figures.max_abs),
                        fixed_cell(r.figures.share_abs_below(1.0)), um_cell(r.figures.mean_abs),
                        fixed_cell(r.figures.share_rel_below(10))});
    }
  }
  print_table_title(out, format,
                    "Beyond the paper: z-score normaliser at fine-tuning, kept from the upstream "
                    "network or refitted on the new surface's training share");
  t.print(out, format);
  std::vector<std::string> configs;
  for (const Run* r : read) configs.push_back(r->record.resolved_yaml);
  std::vector<std::string> notes = {
      "The paper does not say which it does; Tables 4-7 use " + s.manifest.normaliser_default + ".",
      "The runs " + ran_with(s.profile, configs, step_error_settings_keys()) + "."};
  if (s.repeats) {
    for (auto& n : normaliser_seed_notes(*s.repeats)) notes.push_back(n);
  }
  print_table_notes(out, format, notes);
  print_sources(out, format, {}, read);  // no paper numbers here
}

}  // namespace

void print_step_error_study(const StepErrorStudy& study, const TablesOptions& options,
                            std::ostream& out) {
  const TableFormat f = options.format;
  print_table2(study, f, out);
  print_table2_over_seeds(study, f, out);
  print_table2_search(study, f, out);
  print_table3(study, f, out);
  print_fine_tune_table(study, f, out, 2, study.ref.surface2);
  print_bins_at_15(study, f, out, 2);
  print_fine_tune_table(study, f, out, 3, study.ref.surface3);
  print_bins_at_15(study, f, out, 3);
  print_normaliser_table(study, f, out);
  print_step_error_spread(study, f, out);
  print_step_error_table8(study, options, out);
}

void print_step_error_tables(const TablesOptions& options, std::ostream& out) {
  print_step_error_study(load_step_error_study(options), options, out);
}

}  // namespace cnclab
