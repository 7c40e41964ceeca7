#include "cnclab/studies/contour_error/feedrate_sections_tables.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/report/text_table.hpp"
#include "cnclab/report/typed_table.hpp"
#include "cnclab/studies/contour_error/feedrate_job.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// The two studies: the dataset path's validation half, and another seed's path.
struct SectionsStudy {
  const char* key;    // measurement prefix
  const char* file;   // under experiments/
  const char* title;  // what the path is
};
constexpr SectionsStudy kSectionsStudies[] = {
    {"validation_path", "contour_error/any_path/feedrate_sections.yaml",
     "sections of the validation half of the predictor's dataset path"},
    {"unseen_path", "contour_error/any_path/feedrate_unseen_path.yaml",
     "sections of a path of another seed (seen by neither training nor calibration)"},
};

struct SectionsResult {
  const SectionsStudy* study;
  FeedrateJob job;
  StoredResult result;
  std::size_t sections = 0;
};

double sections_metric(const RunRecord& r, const std::string& name) {
  const auto it = r.metrics.find(name);
  return it == r.metrics.end() ? NAN : it->second;
}

// The largest margin of a calibration recorded under `prefix` (every feed
// band, after a reversal too) [µm]; NaN without one.
double sections_largest_margin(const RunRecord& rec, const std::string& prefix) {
  double largest = NAN;
  for (const char* kind : {"margin_band", "margin_after_reversal_band"}) {
    for (std::size_t b = 0; rec.metrics.count(prefix + kind + std::to_string(b)); ++b) {
      const double v = sections_metric(rec, prefix + kind + std::to_string(b));
      largest = std::isnan(largest) ? v : std::max(largest, v);
    }
  }
  return largest;
}

double sections_median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// NaN-propagating minimum (a missing value fails any target).
double sections_min(const std::vector<double>& v) {
  double m = INFINITY;
  for (const double x : v) m = std::isnan(x) || std::isnan(m) ? NAN : std::min(m, x);
  return v.empty() ? NAN : m;
}

// The results present, in kSectionsStudies order; MissingResults (naming
// the command) when there is none. `missing` (if given) receives what is
// absent, so a table of one path says that the other has not run.
std::vector<SectionsResult> sections_results(const TablesOptions& options,
                                             std::string* missing_out = nullptr) {
  std::vector<SectionsResult> out;
  std::string missing;
  for (const SectionsStudy& s : kSectionsStudies) {
    try {
      const fs::path file = options.experiment_file(s.file);
      SectionsResult r{&s, load_feedrate_job(file, {}, options.profile), {}, 0};
      r.result =
          table_store(options).get(ResultKey{r.job.name, std::nullopt, to_yaml(r.job), file, true});
      while (r.result.record.metrics.count(feedrate_section_prefix(r.job, r.sections) + "start")) {
        ++r.sections;
      }
      out.push_back(std::move(r));
    } catch (const MissingResults& e) {
      missing += (missing.empty() ? "" : "; ") + std::string(e.what());
    }
  }
  if (out.empty()) {
    throw MissingResults("the many-section feedrate study has not run (" + missing +
                         "): cnclab reproduce experiments/contour_error/any_path");
  }
  if (missing_out) *missing_out = missing;
  return out;
}

// One tolerance over the sections of one result.
struct ToleranceColumn {
  std::vector<double> share, ratio, oracle;
};

ToleranceColumn tolerance_column(const SectionsResult& r, double tol) {
  ToleranceColumn c;
  const std::string label = feedrate_tolerance_label(tol);
  for (std::size_t k = 0; k < r.sections; ++k) {
    const std::string p = feedrate_section_prefix(r.job, k) + label;
    const double share = sections_metric(r.result.record, p + "_constrained_share_within");
    c.share.push_back(std::isnan(share) ? 0.0 : share);  // not planned: nothing promised
    c.ratio.push_back(sections_metric(r.result.record, p + "_ratio_uniform_constrained"));
    c.oracle.push_back(sections_metric(r.result.record, p + "_ratio_uniform_oracle"));
  }
  return c;
}

double oracle_gain_share(double median_ratio, double median_oracle) {
  if (std::isnan(median_ratio) || std::isnan(median_oracle)) return NAN;
  if (median_oracle > 1.0) return (median_ratio - 1.0) / (median_oracle - 1.0);
  return median_ratio >= median_oracle ? 1.0 : 0.0;
}

void measure_study(const SectionsResult& r, Measurements& m) {
  const std::string key = r.study->key;
  const double required = r.job.verification.required_share - 1e-12;
  std::vector<bool> all(r.sections, true);
  std::vector<double> shares, ratios, gains;
  for (const double tol : r.job.tolerances) {
    const ToleranceColumn c = tolerance_column(r, tol);
    const std::string p = key + "." + feedrate_tolerance_label(tol) + ".";
    double meeting = 0;
    for (std::size_t k = 0; k < r.sections; ++k) {
      const bool met = c.share[k] >= required;
      meeting += met ? 1 : 0;
      all[k] = all[k] && met;
    }
    const double median_ratio = sections_median(c.ratio);
    const double median_oracle = sections_median(c.oracle);
    m[p + "sections_meeting"] = meeting;
    m[p + "median_share_within"] = sections_median(c.share);
    m[p + "min_share_within"] = sections_min(c.share);
    m[p + "median_ratio_uniform_constrained"] = median_ratio;
    m[p + "min_ratio_uniform_constrained"] = sections_min(c.ratio);
    m[p + "median_ratio_uniform_oracle"] = median_oracle;
    m[p + "oracle_gain_share"] = oracle_gain_share(median_ratio, median_oracle);
    shares.insert(shares.end(), c.share.begin(), c.share.end());
    ratios.insert(ratios.end(), c.ratio.begin(), c.ratio.end());
    gains.push_back(m[p + "oracle_gain_share"]);
  }
  m[key + ".sections"] = static_cast<double>(r.sections);
  m[key + ".sections_meeting_all"] = static_cast<double>(std::count(all.begin(), all.end(), true));
  m[key + ".min_share_within"] = sections_min(shares);
  m[key + ".min_ratio_uniform_constrained"] = sections_min(ratios);
  m[key + ".min_oracle_gain_share"] = sections_min(gains);
}

// The predictors on the held-out plans (the first result that has them).
void measure_predictors(const SectionsResult& r, Measurements& m) {
  const RunRecord& rec = r.result.record;
  const double own = sections_metric(rec, "calibration_slowed_rms");
  m["predictor.slowed_underprediction_p99_um"] =
      sections_metric(rec, "calibration_slowed_underprediction_p99");
  m["predictor.slowed_rms_um"] = own;
  m["predictor.max_margin_um"] = sections_largest_margin(rec, "calibration_");
  bool lowest = !std::isnan(own);
  for (std::size_t i = 0; rec.facts.count("compare" + std::to_string(i) + "_name"); ++i) {
    const std::string p = "compare" + std::to_string(i) + "_";
    const std::string name = "compared." + rec.facts.at(p + "name") + ".";
    const double rms = sections_metric(rec, p + "slowed_rms");
    m[name + "slowed_underprediction_p99_um"] =
        sections_metric(rec, p + "slowed_underprediction_p99");
    m[name + "slowed_rms_um"] = rms;
    lowest = lowest && !(rms < own);
  }
  m["predictor.lowest_slowed_rms"] = lowest ? 1.0 : 0.0;
}

TableCell percent_cell(double share) {
  return std::isnan(share) ? missing_cell("-")
                           : number_cell(100 * share, fixed_decimals(100 * share, 2));
}
TableCell ratio_cell(double ratio) {
  return std::isnan(ratio) ? missing_cell("-") : number_cell(ratio, fixed_decimals(ratio, 3));
}

void print_summary(const SectionsResult& r, const Measurements& m, TableFormat format,
                   std::ostream& out) {
  TypedTable t;
  t.columns = {
      number_column("eps_max [µm]", "tolerance", "µm"),
      pair_column(
          "sections >= " + shortest_double(r.job.verification.required_share * 100) + " % within",
          "meeting", "sections"),
      number_column("median within [%]", "median_within", "%"),
      number_column("worst within [%]", "worst_within", "%"),
      number_column("median uniform/constrained", "median_ratio"),
      number_column("worst uniform/constrained", "worst_ratio"),
      number_column("median uniform/oracle", "median_oracle_ratio"),
      number_column("share of oracle gain", "oracle_gain_share")};
  for (const double tol : r.job.tolerances) {
    const std::string p = std::string(r.study->key) + "." + feedrate_tolerance_label(tol) + ".";
    const double meeting = m.at(p + "sections_meeting");
    t.rows.push_back({number_cell(tol, shortest_double(tol)),
                      pair_cell(meeting, static_cast<double>(r.sections),
                                shortest_double(meeting) + "/" + std::to_string(r.sections)),
                      percent_cell(m.at(p + "median_share_within")),
                      percent_cell(m.at(p + "min_share_within")),
                      ratio_cell(m.at(p + "median_ratio_uniform_constrained")),
                      ratio_cell(m.at(p + "min_ratio_uniform_constrained")),
                      ratio_cell(m.at(p + "median_ratio_uniform_oracle")),
                      ratio_cell(m.at(p + "oracle_gain_share"))});
  }
  print_table_title(out, format,
                    "Contour-error constrained feedrate on " + std::to_string(r.sections) + " " +
                        r.study->title + " (" + shortest_double(r.job.sections.length) +
                        " mm each, declared before the run), simulated machine");
  t.print(out, format);
}

void print_sections(const SectionsResult& r, TableFormat format, std::ostream& out) {
  TypedTable t;
  t.columns = {number_column("section start [mm]", "start", "mm")};
  for (const double tol : r.job.tolerances) {
    const std::string e = shortest_double(tol) + " µm";
    const std::string n = feedrate_tolerance_label(tol);
    t.columns.push_back(number_column(e + ": within [%]", n + "_within", "%"));
    t.columns.push_back(number_column(e + ": uniform/constrained", n + "_ratio"));
    t.columns.push_back(number_column(e + ": uniform/oracle", n + "_oracle_ratio"));
  }
  std::vector<ToleranceColumn> cols;
  for (const double tol : r.job.tolerances) cols.push_back(tolerance_column(r, tol));
  for (std::size_t k = 0; k < r.sections; ++k) {
    const double start =
        sections_metric(r.result.record, feedrate_section_prefix(r.job, k) + "start");
    std::vector<TableCell> row = {number_cell(start, fixed_decimals(start, 0))};
    for (const auto& c : cols) {
      row.push_back(percent_cell(c.share[k]));
      row.push_back(ratio_cell(c.ratio[k]));
      row.push_back(ratio_cell(c.oracle[k]));
    }
    t.rows.push_back(std::move(row));
  }
  print_table_title(out, format, "Each section (" + std::string(r.study->title) + ")");
  t.print(out, format);
}

void print_predictors(const SectionsResult& r, TableFormat format, std::ostream& out) {
  const RunRecord& rec = r.result.record;
  TypedTable t;
  t.columns = {label_column("predictor", "predictor"),
               label_column("inputs", "inputs"),
               number_column("held-out slowed: RMS [µm]", "slowed_rms", "µm"),
               number_column("p99 under-prediction [µm]", "slowed_p99", "µm"),
               number_column("correlation", "slowed_correlation"),
               number_column("largest band margin [µm]", "max_margin", "µm")};
  const auto row = [&](const std::string& name, const std::string& inputs, const std::string& p) {
    const double max_margin = sections_largest_margin(rec, p);
    const double rms = sections_metric(rec, p + "slowed_rms");
    const double p99 = sections_metric(rec, p + "slowed_underprediction_p99");
    const double corr = sections_metric(rec, p + "slowed_correlation");
    t.rows.push_back({label_cell(name, name), label_cell(inputs, inputs),
                      number_cell(rms, fixed_decimals(rms, 2)),
                      number_cell(p99, fixed_decimals(p99, 2)),
                      number_cell(corr, fixed_decimals(corr, 3)),
                      number_cell(max_margin, fixed_decimals(max_margin, 2))});
  };
  const auto own_inputs = rec.facts.find("calibration_inputs");  // absent in older results
  row(r.job.predictor + " (plans)", own_inputs == rec.facts.end() ? "" : own_inputs->second,
      "calibration_");
  for (std::size_t i = 0; rec.facts.count("compare" + std::to_string(i) + "_name"); ++i) {
    const std::string p = "compare" + std::to_string(i) + "_";
    row(r.job.compare_predictors.at(i), rec.facts.at(p + "inputs"), p);
  }
  print_table_title(out, format,
                    "The predictors on the held-out plans (the validation halves of the "
                    "planning dataset's runs at every feed factor < 1); the planning predictor "
                    "was chosen by the lowest RMS here");
  t.print(out, format);
  std::vector<std::string> notes;
  std::string margins =
      "margins per feed band (quantile " + shortest_double(r.job.calibration.quantile) + "; edges";
  for (const double e : r.job.calibration.feed_bands) margins += " " + shortest_double(e);
  margins += " mm/s):";
  for (std::size_t b = 0; rec.metrics.count("calibration_margin_band" + std::to_string(b)); ++b) {
    const std::string band = "calibration_margin_band" + std::to_string(b);
    margins += " " + fixed_decimals(sections_metric(rec, band), 2) + " µm (" +
               shortest_double(sections_metric(rec, band + "_ticks")) + " ticks)";
  }
  if (r.job.calibration.reversal_window > 0.0) {
    margins += "; within " + shortest_double(r.job.calibration.reversal_window * 1e3) +
               " ms of a change of direction of either axis:";
    for (std::size_t b = 0;
         rec.metrics.count("calibration_margin_after_reversal_band" + std::to_string(b)); ++b) {
      const std::string band = "calibration_margin_after_reversal_band" + std::to_string(b);
      margins += " " + fixed_decimals(sections_metric(rec, band), 2) + " µm (" +
                 shortest_double(sections_metric(rec, band + "_ticks")) + " ticks)";
    }
  }
  notes.push_back(margins + (r.job.calibrate_margin ? "" : "; not used by this job"));
  print_table_notes(out, format, notes);
}

}  // namespace

Measurements measure_feedrate_sections_tables(const TablesOptions& options) {
  const std::vector<SectionsResult> results = sections_results(options);
  Measurements m;
  // A path that has not run measures NaN (its targets fail, named), and the
  // predictors are compared by the first path's job (the validation half,
  // where compare_predictors is declared) or not at all.
  for (const SectionsStudy& s : kSectionsStudies) {
    for (const char* q : {".sections", ".sections_meeting_all", ".min_share_within",
                          ".min_ratio_uniform_constrained", ".min_oracle_gain_share"}) {
      m[std::string(s.key) + q] = NAN;
    }
  }
  m["predictor.lowest_slowed_rms"] = NAN;
  for (const auto& r : results) measure_study(r, m);
  if (results.front().study == &kSectionsStudies[0]) measure_predictors(results.front(), m);
  return m;
}

void print_feedrate_sections_tables(const TablesOptions& options, std::ostream& out) {
  std::string missing;
  const std::vector<SectionsResult> results = sections_results(options, &missing);
  if (!missing.empty()) {
    // Half the study is not the study: say so before any number.
    print_table_notes(out, options.format,
                      {"not shown, not run with the configs as declared: " + missing +
                       " (cnclab reproduce experiments/contour_error/any_path)"});
  }
  Measurements m;
  for (const auto& r : results) measure_study(r, m);
  std::vector<fs::path> sources;
  for (const auto& r : results) {
    print_summary(r, m, options.format, out);
    std::vector<std::string> notes = {
        "within = share of the 1 ms ticks whose simulated contour error (exact, of the tool "
        "position) is within eps_max; uniform = the unconstrained plan slowed by one factor "
        "found by bisection on the simulated machine; oracle = the same loop with the "
        "simulated machine as a perfect predictor (margin 0): the ceiling of local feed "
        "limits; share of oracle gain = (median ratio - 1) / (oracle's median ratio - 1)",
        "sections: " + std::to_string(r.job.sections.count) + " evenly spaced over " +
            (r.job.sections.span == SectionSpan::validation
                 ? "the arc lengths of the dataset path's validation half"
                 : "the whole path") +
            ", declared before the run" +
            (r.job.path.seed
                 ? "; path drawn from seed " + std::to_string(*r.job.path.seed) + " (the test)"
                 : std::string("; the path whose held-out plans calibrated the "
                               "margins and chose the inputs (validation, not a "
                               "test)")) +
            "; margin " +
            (r.job.calibrate_margin ? std::string("calibrated per feed band (below)")
                                    : shortest_double(r.job.prediction_margin) + " µm") +
            "; job wall " + fixed_decimals(sections_metric(r.result.record, "wall_seconds"), 0) +
            " s"};
    print_table_notes(out, options.format, notes);
    print_sections(r, options.format, out);
    sources.push_back(r.result.file);
  }
  // The comparison is the validation-half job's (compare_predictors).
  if (results.front().study == &kSectionsStudies[0]) {
    print_predictors(results.front(), options.format, out);
  }
  print_table_sources(out, options.format, sources);
}

}  // namespace cnclab
