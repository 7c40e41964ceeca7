#include "cnclab/studies/contour_error/contour_error_tables.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/report/run_settings.hpp"
#include "cnclab/report/typed_table.hpp"
#include "cnclab/studies/contour_error/narx_study_runs.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr double kMissingCell = std::numeric_limits<double>::quiet_NaN();

constexpr const char* kRetryNote =
    "_retry: a closed-loop stage that stops on mu_max or diverges is trained again from its "
    "starting weights, on 1000-step windows each predicted from measured states, then on the "
    "whole series, and the lower whole-series SSE is kept (trainer.stages fallback_horizon). "
    "The open-loop weights of some seeds make a closed loop whose RTRL Jacobian grows to 1e20 "
    "along the 86,000 steps, and LM stops on mu_max (docs/narx_training.md)";

// One note per run that is not stable: how its training ended, so that a
// training stop (mu_max, diverged) is told from a network that trained to its
// epoch cap and still predicts the validation half badly.
std::vector<std::string> unstable_notes(const NarxStudyRuns& r) {
  std::vector<std::string> notes;
  for (const auto& run : r.runs) {
    if (r.stable(run)) continue;
    const bool stopped = run.stops.find("mu_max") != std::string::npos ||
                         run.stops.find("diverged") != std::string::npos;
    notes.push_back(
        "not stable: " + run.method + " H=" + std::to_string(run.hidden) +
        " D=" + std::to_string(run.input_delays) + " seed " + std::to_string(run.seed) +
        ", training ended " + run.stops +
        (stopped ? "" : " (no early stop: the error is in predicting the validation half)"));
  }
  return notes;
}

// "second tries: N of M networks (run ...)": who needed fallback_horizon.
std::string second_try_note(const NarxStudyRuns& r) {
  std::size_t tried = 0, networks = 0;
  std::string which;
  for (const auto& run : r.runs) {
    networks += r.axes.size();
    tried += run.second_tries;
    if (run.second_tries > 0) {
      which += (which.empty() ? "" : ", ") + run.method + " H=" + std::to_string(run.hidden) +
               " D=" + std::to_string(run.input_delays) + " seed " + std::to_string(run.seed);
    }
  }
  return "second tries: " + std::to_string(tried) + " of " + std::to_string(networks) +
         " networks" + (which.empty() ? "" : " (" + which + ")");
}

struct Stats {
  double mean = kMissingCell, std = kMissingCell, min = kMissingCell, max = kMissingCell;
  std::size_t n = 0;
};
Stats stats(const std::vector<double>& v) {
  Stats s;
  std::vector<double> ok;
  for (double x : v) {
    if (std::isfinite(x)) ok.push_back(x);
  }
  s.n = ok.size();
  if (ok.empty()) return s;
  double sum = 0;
  for (double x : ok) sum += x;
  s.mean = sum / static_cast<double>(ok.size());
  double sq = 0;
  for (double x : ok) sq += (x - s.mean) * (x - s.mean);
  s.std = ok.size() > 1 ? std::sqrt(sq / static_cast<double>(ok.size() - 1)) : 0.0;
  s.min = *std::min_element(ok.begin(), ok.end());
  s.max = *std::max_element(ok.begin(), ok.end());
  return s;
}
TableCell mean_std(const Stats& s) {
  if (s.n == 0) return missing_cell("-");
  return mean_std_cell(s.mean, s.std, table_number(s.mean, 3) + " ± " + table_number(s.std, 2));
}

// A single number in µm, 3 significant digits as the paper's text.
TableCell um3(double v) {
  return number_cell(v, table_number(v, 3));
}

// The runs of training method `method`.
std::vector<const NarxStudyRun*> runs_of(const NarxStudyRuns& r, const std::string& method) {
  std::vector<const NarxStudyRun*> runs;
  for (const auto& run : r.runs) {
    if (run.method == method) runs.push_back(&run);
  }
  return runs;
}

// The metric `name` of each run.
std::vector<double> metric_of(const std::vector<const NarxStudyRun*>& runs,
                              const std::string& name) {
  std::vector<double> v;
  for (const auto* run : runs) v.push_back(run->metrics.at(name));
  return v;
}

// "4/5": stable runs of all (csv/json: stable, runs).
TableCell stable_count(const NarxStudyRuns& study, const std::vector<const NarxStudyRun*>& runs) {
  const auto stable = std::count_if(runs.begin(), runs.end(),
                                    [&](const NarxStudyRun* r) { return study.stable(*r); });
  return pair_cell(static_cast<double>(stable), static_cast<double>(runs.size()),
                   std::to_string(stable) + "/" + std::to_string(runs.size()));
}

std::string stable_note() {
  return "stable: the closed-loop prediction stayed bounded and every axis's RMS is within " +
         table_number(kStableFactor, 3) +
         "x the best run's of this table (a bounded network with large errors counts as failed, "
         "as in the paper); mean ± std are over the bounded runs, stable or not";
}

// "The runs ran with profile quick (per the result files' configs): dataset:
// ...; model: ..." of the study's runs (report/run_settings.hpp).
std::string settings_note(const NarxStudyRuns& r) {
  return "The runs " + ran_with(r.profile, r.configs,
                                {"dataset.options.samples", "dataset.options.runs",
                                 "dataset.options.path.control_points", "model.hidden",
                                 "model.input_delays", "model.feedback_delays"});
}

// `notes`, then the notes both study tables end with (what "stable" means,
// the second try, each run that is not stable, each trial that did not
// complete), then the files read.
void print_training_notes(const NarxStudyRuns& r, std::vector<std::string> notes, TableFormat f,
                          std::ostream& out) {
  notes.push_back(settings_note(r) + "; their trainer stages give the epochs column.");
  notes.push_back(stable_note());
  notes.push_back(kRetryNote);
  notes.push_back(second_try_note(r));
  for (auto& n : unstable_notes(r)) notes.push_back(std::move(n));
  if (!r.not_completed.empty()) {
    notes.push_back(std::to_string(r.not_completed.size()) + " of " + std::to_string(r.trials) +
                    " planned trials did not complete and are not in the table (nor in its "
                    "stable counts):");
    for (const auto& n : r.not_completed) notes.push_back(n);
  }
  print_table_notes(out, f, notes);
  print_table_sources(out, f, r.sources);
}

std::string reference_text(const ConfigReader& root, const std::string& section,
                           const std::string& key) {
  const ConfigReader s = root.section(section).section(key);
  return s.require<std::string>("text") + " (" + s.require<std::string>("source") + ")";
}

void print_training_methods(const NarxStudyRuns& r, const ConfigReader& ref, TableFormat f,
                            std::ostream& out) {
  print_table_title(out, f,
                    "Contour error (seed 002 Sec. II): NARX training methods, " +
                        std::to_string(r.runs.size()) +
                        " runs; closed-loop prediction of the whole validation half (" +
                        std::to_string(r.validation_samples) + " steps; trained on " +
                        std::to_string(r.train_samples) +
                        "). Simulated machine biaxial_router; errors in µm, mean ± std.");
  TypedTable t;
  t.columns = {label_column("method", "method"), pair_column("stable", "stable", "runs")};
  for (const auto& a : r.axes) {
    t.columns.push_back(mean_std_column("RMS " + a, "rms_" + a, "um"));
    t.columns.push_back(mean_std_column("max " + a, "max_" + a, "um"));
  }
  t.columns.push_back(mean_std_column("contour RMS", "contour_rms", "um"));
  t.columns.push_back(pair_column("epochs open+closed", "open_epochs", "closed_epochs"));
  for (const char* m : {"two_stage", "two_stage_retry", "two_stage_windowed", "open_loop_only",
                        "closed_loop_only", "closed_loop_only_windowed"}) {
    const std::vector<const NarxStudyRun*> runs = runs_of(r, m);
    if (runs.empty()) continue;
    std::vector<TableCell> row = {m, stable_count(r, runs)};
    for (const auto& a : r.axes) {
      row.push_back(mean_std(stats(metric_of(runs, "closed_loop_rms_" + a))));
      row.push_back(mean_std(stats(metric_of(runs, "closed_loop_max_" + a))));
    }
    row.push_back(mean_std(stats(metric_of(runs, "contour_rms"))));
    row.push_back(pair_cell(
        static_cast<double>(runs[0]->open_epochs), static_cast<double>(runs[0]->closed_epochs),
        std::to_string(runs[0]->open_epochs) + "+" + std::to_string(runs[0]->closed_epochs)));
    t.rows.push_back(row);
  }
  // One value where the methods have mean ± std: csv/json carry it as the mean.
  std::vector<TableCell> zero = {label_cell("zero predictor (e = 0)", "zero_predictor"),
                                 missing_cell("-")};
  for (const auto& a : r.axes) {
    zero.push_back(um3(r.metric("zero_rms_" + a)));
    zero.push_back(um3(r.metric("zero_max_" + a)));
  }
  zero.push_back(missing_cell("-"));
  zero.push_back(missing_cell("-"));
  t.rows.push_back(zero);
  t.print(out, f);
  std::vector<std::string> notes = {
      "Paper, two_stage: " + reference_text(ref, "training_methods", "two_stage"),
      "Paper, closed_loop_only: " + reference_text(ref, "training_methods", "closed_loop_only"),
      "Paper, open_loop_only: " + reference_text(ref, "training_methods", "open_loop_only")};
  print_training_notes(r, std::move(notes), f, out);
}

void print_architecture(const NarxStudyRuns& r, const ConfigReader& ref, TableFormat f,
                        std::ostream& out) {
  print_table_title(out, f,
                    "Contour error: NARX architecture sweep (trainbr), mean over seeds, µm");
  TypedTable t;
  t.columns = {number_column("hidden", "hidden"),
               pair_column("delays (in/fb)", "input_delays", "feedback_delays"),
               number_column("parameters", "parameters"), pair_column("stable", "stable", "runs")};
  for (const auto& a : r.axes) t.columns.push_back(mean_std_column("RMS " + a, "rms_" + a, "um"));
  t.columns.push_back(mean_std_column("contour RMS", "contour_rms", "um"));
  t.columns.push_back(number_column("paper", "paper_choice"));  // 1: the paper's architecture
  t.columns.push_back(number_column("chosen", "chosen"));       // 1: the sweep's choice
  const auto same_architecture = [](const NarxStudyRun& a, const NarxStudyRun& b) {
    return a.hidden == b.hidden && a.input_delays == b.input_delays &&
           a.feedback_delays == b.feedback_delays;
  };
  const auto paper_h = ref.section("architecture").section("hidden").require<std::size_t>("value");
  const auto paper_d =
      ref.section("architecture").section("input_delays").require<std::size_t>("value");
  std::vector<const NarxStudyRun*> shown;  // one run per architecture, in plan order
  for (const auto& run : r.runs) {
    if (std::none_of(shown.begin(), shown.end(),
                     [&](const NarxStudyRun* k) { return same_architecture(*k, run); })) {
      shown.push_back(&run);
    }
  }
  for (const NarxStudyRun* k : shown) {
    std::vector<const NarxStudyRun*> runs;
    for (const auto& run : r.runs) {
      if (same_architecture(*k, run)) runs.push_back(&run);
    }
    const std::size_t h = k->hidden, di = k->input_delays, df = k->feedback_delays;
    const std::size_t params = h * (di + df) + 2 * h + 1;
    const auto count = [](std::size_t n) {
      return number_cell(static_cast<double>(n), std::to_string(n));
    };
    std::vector<TableCell> row = {count(h),
                                  pair_cell(static_cast<double>(di), static_cast<double>(df),
                                            std::to_string(di) + "/" + std::to_string(df)),
                                  count(params), stable_count(r, runs)};
    for (const auto& a : r.axes) {
      row.push_back(mean_std(stats(metric_of(runs, "closed_loop_rms_" + a))));
    }
    row.push_back(mean_std(stats(metric_of(runs, "contour_rms"))));
    const bool papers = h == paper_h && di == paper_d && df == paper_d;
    const bool chosen = r.chosen && same_architecture(*k, r.runs[*r.chosen]);
    row.push_back(number_cell(papers ? 1 : 0, papers ? "<- paper's choice" : ""));
    row.push_back(number_cell(chosen ? 1 : 0, chosen ? "<- chosen on validation" : ""));
    t.rows.push_back(row);
  }
  t.print(out, f);
  std::vector<std::string> notes = {
      "Paper: " + std::to_string(paper_h) + " tanh neurons, " + std::to_string(paper_d) +
          " input and feedback delays: " + reference_text(ref, "architecture", "claim"),
      "Training: " + (r.runs.empty() ? std::string("-") : r.runs.front().method) +
          " (experiments/contour_error/architecture.yaml)"};
  if (r.chosen) {
    const NarxStudyRun& c = r.runs[*r.chosen];
    const bool same =
        c.hidden == paper_h && c.input_delays == paper_d && c.feedback_delays == paper_d;
    notes.push_back("Chosen on validation: H=" + std::to_string(c.hidden) + ", delays " +
                    std::to_string(c.input_delays) + "/" + std::to_string(c.feedback_delays) +
                    ", the lowest mean " + r.objective +
                    " (the sweep's objective; unstable runs rank last)" +
                    (same ? ", the paper's choice too."
                          : "; the paper chose H=" + std::to_string(paper_h) + ", delays " +
                                std::to_string(paper_d) + "/" + std::to_string(paper_d) + "."));
  }
  notes.push_back(
      "No test split: seed 002 trains on the first half and reports the second (sequential "
      "halves), and no training stage stops on it, so it is held out; but both choices above "
      "are made on that half, the half every number here is measured on: the chosen "
      "architecture's numbers are optimistic, not an estimate on new data.");
  print_training_notes(r, std::move(notes), f, out);
}

void print_estimates(const NarxStudyRuns& r, const ConfigReader& ref, TableFormat f,
                     std::ostream& out) {
  print_table_title(out, f,
                    "Contour error estimates vs the exact contour error (Newton projection) on the "
                    "simulated data, validation half, µm");
  TypedTable t;
  t.columns = {label_column("estimate", "estimate"),
               number_column("mean |est - exact|", "mean_abs_diff", "um"),
               number_column("max |est - exact|", "max_abs_diff", "um")};
  for (const std::string e : {"taylor", "tangent", "osculating"}) {
    t.rows.push_back({e, um3(r.metric(e + "_mean_abs_diff")), um3(r.metric(e + "_max_abs_diff"))});
  }
  const double exact_mean = r.metric("exact_contour_mean"),
               exact_max = r.metric("exact_contour_max");
  t.rows.push_back({label_cell("(exact contour error itself)", "exact_contour_error"),
                    number_cell(exact_mean, table_number(exact_mean, 3) + " (mean)"),
                    number_cell(exact_max, table_number(exact_max, 3) + " (max)")});
  t.print(out, f);
  print_table_notes(out, f,
                    {"Paper: " + reference_text(ref, "contour", "estimate"),
                     settings_note(r) + " (the estimates use their simulated data)."});
}

void print_predictor(const NarxStudyRuns& r, const ConfigReader& ref, TableFormat f,
                     std::ostream& out) {
  print_table_title(out, f,
                    "Contour error predictor (Taylor estimate from the NARX-predicted following "
                    "errors) vs the \"actual\" (exact, simulated) contour error, validation half, "
                    "µm");
  TypedTable t;
  t.columns = {label_column("method", "method"),
               pair_column("stable", "stable", "runs"),
               mean_std_column("RMS (mean ± std)", "rms", "um"),
               number_column("RMS best", "rms_best", "um"),
               mean_std_column("max (mean ± std)", "max", "um"),
               number_column("zero predictor RMS", "zero_predictor_rms", "um")};
  // The two-stage methods (the paper's, and with the second try that the
  // studies use); stable as in the training-methods table.
  for (const std::string method : {"two_stage", "two_stage_retry"}) {
    const std::vector<const NarxStudyRun*> runs = runs_of(r, method);
    if (runs.empty()) continue;
    const Stats s = stats(metric_of(runs, "contour_rms"));
    // Predicting zero following error predicts zero contour error: its RMS
    // is the exact contour error's RMS.
    t.rows.push_back({method, stable_count(r, runs), mean_std(s), um3(s.min),
                      mean_std(stats(metric_of(runs, "contour_max"))), missing_cell("see note")});
  }
  t.print(out, f);
  print_table_notes(out, f,
                    {"zero predictor: contour RMS = RMS of the exact contour error; its mean is " +
                         table_number(r.metric("exact_contour_mean"), 3) + " µm, max " +
                         table_number(r.metric("exact_contour_max"), 3) + " µm",
                     stable_note(), "Paper: " + reference_text(ref, "contour", "accuracy"),
                     settings_note(r) + "."});
}

// The measured quantities of one group of runs (a method, an architecture)
// under `prefix`, with the same stats() and stable() as the rows.
void add_group(Measurements& m, const std::string& prefix, const NarxStudyRuns& r,
               const std::vector<const NarxStudyRun*>& runs) {
  const auto stable =
      std::count_if(runs.begin(), runs.end(), [&](const NarxStudyRun* x) { return r.stable(*x); });
  const auto bounded =
      std::count_if(runs.begin(), runs.end(), [](const NarxStudyRun* x) { return x->bounded(); });
  m[prefix + ".runs"] = static_cast<double>(runs.size());
  m[prefix + ".stable_runs"] = static_cast<double>(stable);
  m[prefix + ".bounded_runs"] = static_cast<double>(bounded);
  const auto add_stats = [&](const std::string& name, const std::string& metric) {
    const Stats st = stats(metric_of(runs, metric));
    m[prefix + "." + name + "_mean"] = st.mean;
    m[prefix + "." + name + "_std"] = st.std;
  };
  for (const auto& a : r.axes) {
    add_stats("rms_" + a, "closed_loop_rms_" + a);
    add_stats("max_" + a, "closed_loop_max_" + a);
  }
  add_stats("contour_rms", "contour_rms");
}

// training_methods.<method>.* per method (add_group), training_methods.second_tries,
// training_methods.zero_rms_<axis>, estimates.<taylor|tangent|osculating>.{mean,max}_abs_diff.
void add_methods(Measurements& m, const NarxStudyRuns& r) {
  std::map<std::string, std::vector<const NarxStudyRun*>> by_method;
  std::size_t tries = 0;
  for (const auto& run : r.runs) {
    by_method[run.method].push_back(&run);
    tries += run.second_tries;
  }
  for (const auto& [method, runs] : by_method) add_group(m, "training_methods." + method, r, runs);
  m["training_methods.second_tries"] = static_cast<double>(tries);
  for (const auto& a : r.axes) m["training_methods.zero_rms_" + a] = r.metric("zero_rms_" + a);
  for (const std::string e : {"taylor", "tangent", "osculating"}) {
    m["estimates." + e + ".mean_abs_diff"] = r.metric(e + "_mean_abs_diff");
    m["estimates." + e + ".max_abs_diff"] = r.metric(e + "_max_abs_diff");
  }
}

// architecture.h<H>_d<in>_<fb>.* per architecture, architecture.all.* over every run,
// architecture.chosen.{hidden,delays}: the sweep's choice on validation (input delays).
void add_architectures(Measurements& m, const NarxStudyRuns& r) {
  std::map<std::string, std::vector<const NarxStudyRun*>> by_arch;
  std::vector<const NarxStudyRun*> all;
  for (const auto& run : r.runs) {
    // Appended, not `"h" + std::to_string`: GCC 12 warns falsely (-Wrestrict, PR105329).
    std::string arch = "h";
    arch += std::to_string(run.hidden);
    arch += "_d" + std::to_string(run.input_delays) + "_" + std::to_string(run.feedback_delays);
    by_arch[arch].push_back(&run);
    all.push_back(&run);
  }
  for (const auto& [arch, runs] : by_arch) add_group(m, "architecture." + arch, r, runs);
  add_group(m, "architecture.all", r, all);
  if (r.chosen) {
    m["architecture.chosen.hidden"] = static_cast<double>(r.runs[*r.chosen].hidden);
    m["architecture.chosen.delays"] = static_cast<double>(r.runs[*r.chosen].input_delays);
  }
}

}  // namespace

void print_contour_error_tables(const TablesOptions& o, std::ostream& out) {
  const fs::path ref_file = o.reference_file("seed002_contour_error.yaml");
  if (!fs::exists(ref_file)) throw MissingResults(ref_file.string() + ": not found");
  const ConfigDocument ref_doc = ConfigDocument::load(ref_file);
  const ConfigReader ref = ref_doc.root();
  const NarxStudyRuns methods = load_narx_study(o, "training_methods.yaml");
  print_training_methods(methods, ref, o.format, out);
  try {
    print_architecture(load_narx_study(o, "architecture.yaml"), ref, o.format, out);
  } catch (const MissingResults& e) {
    print_table_notes(out, o.format, {"architecture table not printed: " + std::string(e.what())});
  }
  print_estimates(methods, ref, o.format, out);
  print_predictor(methods, ref, o.format, out);
}

Measurements measure_contour_error_tables(const TablesOptions& o) {
  Measurements m;
  add_methods(m, load_narx_study(o, "training_methods.yaml"));
  try {
    add_architectures(m, load_narx_study(o, "architecture.yaml"));
  } catch (const MissingResults&) {
    // As the tables: the architecture table is optional; a target naming
    // its quantities then reports them unknown.
  }
  return m;
}

}  // namespace cnclab
