#include "cnclab/studies/contour_error/contour_error_tables.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/report/text_table.hpp"
#include "cnclab/studies/contour_error/narx_job.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr double kMissingCell = std::numeric_limits<double>::quiet_NaN();

// The result of experiments/contour_error/<file>: the one of the file's
// resolved config, else (a profile such as quick changes the config) the
// newest complete result under <results>/<name>/.
NarxStudyResult load_study(const TablesOptions& o, const std::string& file) {
  const fs::path experiment = o.experiments_dir / "contour_error" / file;
  if (!fs::exists(experiment)) throw MissingResults(experiment.string() + ": not found");
  const NarxJob job = load_narx_job(experiment, {}, o.profile);
  const fs::path exact = narx_result_path(job, o.results_dir);
  if (fs::exists(exact)) return read_narx_result(exact);
  const fs::path dir = o.results_dir / job.name;
  std::error_code ec;
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.path().extension() == ".h5" && !is_partial_path(e.path())) found.push_back(e.path());
  }
  std::sort(found.begin(), found.end(), [](const fs::path& a, const fs::path& b) {
    return fs::last_write_time(a) > fs::last_write_time(b);
  });
  for (const auto& f : found) {
    try {
      return read_narx_result(f);
    } catch (const IoError&) {
    }
  }
  throw MissingResults("no result for " + experiment.string() + " under " + dir.string() +
                       "; run `cnclab reproduce " + (o.experiments_dir / "contour_error").string() +
                       "` first");
}

struct Stats {
  double mean = kMissingCell, std = kMissingCell, max = kMissingCell;
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
  s.max = *std::max_element(ok.begin(), ok.end());
  return s;
}
std::string mean_std(const Stats& s) {
  if (s.n == 0) return "-";
  return table_number(s.mean, 3) + " ± " + table_number(s.std, 2);
}

bool run_stable(const NarxRun& r) {
  return std::all_of(r.axes.begin(), r.axes.end(), [](const NarxAxisScore& s) { return s.stable; });
}

std::string reference_text(const ConfigReader& root, const std::string& section,
                           const std::string& key) {
  const ConfigReader s = root.section(section).section(key);
  return s.require<std::string>("text") + " (" + s.require<std::string>("source") + ")";
}

void print_training_methods(const NarxStudyResult& r, const ConfigReader& ref, TableFormat f,
                            std::ostream& out) {
  print_table_title(out, f,
                    "Contour error (seed 002 Sec. II): NARX training methods, " +
                        std::to_string(r.runs.size()) +
                        " runs; closed-loop prediction of the whole validation half (" +
                        std::to_string(r.validation_samples) + " steps; trained on " +
                        std::to_string(r.train_samples) +
                        "). Simulated machine biaxial_router; errors in µm, mean ± std over the "
                        "stable runs.");
  TextTable t;
  t.header = {"method", "stable"};
  for (const auto& a : r.axes) {
    t.header.push_back("RMS " + a);
    t.header.push_back("max " + a);
  }
  t.header.push_back("contour RMS");
  t.header.push_back("epochs open+closed");
  for (const char* m : {"two_stage", "open_loop_only", "closed_loop_only"}) {
    std::vector<const NarxRun*> runs;
    for (const auto& run : r.runs) {
      if (to_string(run.method) == m) runs.push_back(&run);
    }
    if (runs.empty()) continue;
    std::size_t stable = 0;
    for (const auto* run : runs) stable += run_stable(*run) ? 1 : 0;
    std::vector<std::string> row = {m, std::to_string(stable) + "/" + std::to_string(runs.size())};
    for (std::size_t a = 0; a < r.axes.size(); ++a) {
      std::vector<double> rms, mx;
      for (const auto* run : runs) {
        rms.push_back(run->axes[a].rms_um);
        mx.push_back(run->axes[a].max_um);
      }
      row.push_back(mean_std(stats(rms)));
      row.push_back(mean_std(stats(mx)));
    }
    std::vector<double> c;
    for (const auto* run : runs) c.push_back(run->contour_rms_um);
    row.push_back(mean_std(stats(c)));
    row.push_back(std::to_string(runs[0]->axes[0].open_epochs) + "+" +
                  std::to_string(runs[0]->axes[0].closed_epochs));
    t.rows.push_back(row);
  }
  std::vector<std::string> zero = {"zero predictor (e = 0)", "-"};
  for (std::size_t a = 0; a < r.axes.size(); ++a) {
    zero.push_back(table_number(r.zero_rms_um[a], 3));
    zero.push_back(table_number(r.zero_max_um[a], 3));
  }
  zero.push_back("-");
  zero.push_back("-");
  t.rows.push_back(zero);
  t.print(out, f);
  print_table_notes(
      out, f,
      {"Paper, two_stage: " + reference_text(ref, "training_methods", "two_stage"),
       "Paper, closed_loop_only: " + reference_text(ref, "training_methods", "closed_loop_only"),
       "Paper, open_loop_only: " + reference_text(ref, "training_methods", "open_loop_only")});
}

void print_architecture(const NarxStudyResult& r, const ConfigReader& ref, TableFormat f,
                        std::ostream& out) {
  print_table_title(out, f,
                    "Contour error: NARX architecture sweep (two-stage trainbr), mean over seeds, "
                    "µm");
  TextTable t;
  t.header = {"hidden", "delays (in/fb)", "parameters", "stable"};
  for (const auto& a : r.axes) t.header.push_back("RMS " + a);
  t.header.push_back("contour RMS");
  t.header.push_back("");
  struct Key {
    std::size_t h, di, df;
  };
  std::vector<Key> keys;
  for (const auto& run : r.runs) {
    const Key k{run.architecture.hidden, run.architecture.input_delays,
                run.architecture.feedback_delays};
    if (std::none_of(keys.begin(), keys.end(),
                     [&](const Key& o) { return o.h == k.h && o.di == k.di && o.df == k.df; })) {
      keys.push_back(k);
    }
  }
  const auto paper_h = ref.section("architecture").section("hidden").require<std::size_t>("value");
  const auto paper_d =
      ref.section("architecture").section("input_delays").require<std::size_t>("value");
  for (const Key& k : keys) {
    std::vector<const NarxRun*> runs;
    for (const auto& run : r.runs) {
      if (run.architecture.hidden == k.h && run.architecture.input_delays == k.di &&
          run.architecture.feedback_delays == k.df) {
        runs.push_back(&run);
      }
    }
    std::size_t stable = 0;
    for (const auto* run : runs) stable += run_stable(*run) ? 1 : 0;
    const std::size_t params = k.h * (k.di + k.df) + 2 * k.h + 1;
    std::vector<std::string> row = {
        std::to_string(k.h), std::to_string(k.di) + "/" + std::to_string(k.df),
        std::to_string(params), std::to_string(stable) + "/" + std::to_string(runs.size())};
    for (std::size_t a = 0; a < r.axes.size(); ++a) {
      std::vector<double> rms;
      for (const auto* run : runs) rms.push_back(run->axes[a].rms_um);
      row.push_back(mean_std(stats(rms)));
    }
    std::vector<double> c;
    for (const auto* run : runs) c.push_back(run->contour_rms_um);
    row.push_back(mean_std(stats(c)));
    row.push_back(k.h == paper_h && k.di == paper_d && k.df == paper_d ? "<- paper's choice" : "");
    t.rows.push_back(row);
  }
  t.print(out, f);
  print_table_notes(
      out, f,
      {"Paper: " + std::to_string(paper_h) + " tanh neurons, " + std::to_string(paper_d) +
       " input and feedback delays: " + reference_text(ref, "architecture", "claim")});
}

void print_estimates(const NarxStudyResult& r, const ConfigReader& ref, TableFormat f,
                     std::ostream& out) {
  print_table_title(out, f,
                    "Contour error estimates vs the exact contour error (Newton projection) on the "
                    "simulated data, validation half, µm");
  TextTable t;
  t.header = {"estimate", "mean |est - exact|", "max |est - exact|"};
  for (const auto& e : r.estimates) {
    t.rows.push_back({e.method, table_number(e.mean_um, 3), table_number(e.max_um, 3)});
  }
  t.rows.push_back({"(exact contour error itself)",
                    table_number(r.exact_contour_mean_um, 3) + " (mean)",
                    table_number(r.exact_contour_max_um, 3) + " (max)"});
  t.print(out, f);
  print_table_notes(out, f, {"Paper: " + reference_text(ref, "contour", "estimate")});
}

void print_predictor(const NarxStudyResult& r, const ConfigReader& ref, TableFormat f,
                     std::ostream& out) {
  print_table_title(out, f,
                    "Contour error predictor (Taylor estimate from the NARX-predicted following "
                    "errors) vs the \"actual\" (exact, simulated) contour error, validation half, "
                    "µm");
  TextTable t;
  t.header = {"runs", "RMS (mean ± std)", "RMS best", "max (mean ± std)", "zero predictor RMS"};
  std::vector<double> rms, mx;
  for (const auto& run : r.runs) {
    if (run.method != NarxMethod::two_stage) continue;
    rms.push_back(run.contour_rms_um);
    mx.push_back(run.contour_max_um);
  }
  const Stats s = stats(rms);
  const double best =
      s.n ? *std::min_element(
                rms.begin(), rms.end(),
                [](double a, double b) { return std::isfinite(a) && (!std::isfinite(b) || a < b); })
          : kMissingCell;
  // Predicting zero following error predicts zero contour error: its RMS is
  // the exact contour error's RMS.
  t.rows.push_back({"two_stage, " + std::to_string(s.n) + " stable", mean_std(s),
                    table_number(best, 3), mean_std(stats(mx)), "see note"});
  t.print(out, f);
  print_table_notes(out, f,
                    {"zero predictor: contour RMS = RMS of the exact contour error; its mean is " +
                         table_number(r.exact_contour_mean_um, 3) + " µm, max " +
                         table_number(r.exact_contour_max_um, 3) + " µm",
                     "Paper: " + reference_text(ref, "contour", "accuracy")});
}

}  // namespace

void print_contour_error_tables(const TablesOptions& o, std::ostream& out) {
  const fs::path ref_file = o.reference_dir / "seed002_contour_error.yaml";
  if (!fs::exists(ref_file)) throw MissingResults(ref_file.string() + ": not found");
  const ConfigDocument ref_doc = ConfigDocument::load(ref_file);
  const ConfigReader ref = ref_doc.root();
  const NarxStudyResult methods = load_study(o, "training_methods.yaml");
  print_training_methods(methods, ref, o.format, out);
  try {
    print_architecture(load_study(o, "architecture.yaml"), ref, o.format, out);
  } catch (const MissingResults& e) {
    print_table_notes(out, o.format, {"architecture table not printed: " + std::string(e.what())});
  }
  print_estimates(methods, ref, o.format, out);
  print_predictor(methods, ref, o.format, out);
}

}  // namespace cnclab
