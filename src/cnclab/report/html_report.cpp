#include "cnclab/report/html_report.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/run_warnings.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/provenance.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/report/html_page.hpp"
#include "cnclab/report/parameter_importance.hpp"
#include "cnclab/report/study_figures.hpp"
#include "cnclab/report/targets.hpp"
#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

namespace cnclab {
namespace fs = std::filesystem;

namespace {

struct Builder {
  HtmlPage page;
  std::size_t failed_targets = 0;
  std::set<std::string> runs_shown;
};

std::vector<std::string> markdown_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  for (std::size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
      cell += '|';
      ++i;
    } else if (line[i] == '|') {
      const auto b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
      cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
      cell.clear();
    } else {
      cell += line[i];
    }
  }
  return cells;
}

// Whether `file`'s run is not on the page yet (and from now on it is).
bool first_showing(Builder& b, const fs::path& file) {
  return b.runs_shown.insert(fs::absolute(file).lexically_normal().string()).second;
}

// The run behind a number (`r`, read from `file`): provenance, metrics,
// training history.
void add_run(Builder& b, const fs::path& file, const RunRecord& r, int level) {
  // A sweep trial keeps its base experiment's name: the overrides in the heading say which
  // point of the sweep it is (e.g. keep 0.8 of a sweep whose base file is named keep_0.5).
  std::string heading = "Run " + r.experiment;
  if (!r.provenance.overrides.empty()) {
    std::string joined;
    for (const auto& o : r.provenance.overrides) joined += (joined.empty() ? "" : ", ") + o;
    heading += " [" + joined + "]";
  }
  b.page.heading(level, heading + " — " + file.filename().string(), "");
  std::vector<std::pair<std::string, std::string>> facts = {
      {"result file", file.string()},
      {"status",
       status_text(r.provenance.status, r.warnings) +
           (r.provenance.failure_reason.empty() ? "" : ": " + r.provenance.failure_reason)},
      {"identity", "config hash " + r.config_hash}};
  for (const auto& line : provenance_lines(r.provenance)) facts.push_back(line);
  b.page.definitions(facts);
  if (!r.metrics.empty()) {
    TextTable m;
    m.header = {"metric", "value", "unit"};
    for (const auto& [name, value] : r.metrics) {
      const auto u = r.metric_units.find(name);
      m.rows.push_back({name, format_metric(value), u == r.metric_units.end() ? "" : u->second});
    }
    b.page.table(m, "metrics");
  }
  std::vector<ChartSeries> loss;
  const auto history = [&](const Summary& s, const std::string& prefix) {
    ChartSeries train{prefix + "training", {}}, validation{prefix + "validation", {}};
    for (const auto& e : s.history) {
      train.points.emplace_back(static_cast<double>(e.epoch), e.train_loss);
      validation.points.emplace_back(static_cast<double>(e.epoch), e.validation_loss);
    }
    if (!train.points.empty()) loss.push_back(std::move(train));
    if (std::any_of(validation.points.begin(), validation.points.end(),
                    [](const auto& p) { return std::isfinite(p.second); }))
      loss.push_back(std::move(validation));
    if (!s.lm_history.empty()) {
      ChartSeries mu{prefix + "μ", {}}, gamma{prefix + "γ", {}};
      for (std::size_t i = 0; i < s.lm_history.size(); ++i) {
        mu.points.emplace_back(static_cast<double>(i + 1), s.lm_history[i].mu);
        gamma.points.emplace_back(static_cast<double>(i + 1), s.lm_history[i].gamma);
      }
      b.page.figure(svg_line_chart({mu}, {prefix + "LM damping μ per epoch", "epoch", "μ", true}),
                    "Levenberg-Marquardt damping μ after each epoch's accepted step");
      b.page.figure(
          svg_line_chart({gamma}, {prefix + "effective parameters γ", "epoch", "γ", false}),
          "effective number of parameters γ per epoch (with Bayesian regularisation; without "
          "it, γ = N_w, every weight)");
    }
  };
  if (r.narx) {
    for (const auto& n : r.narx->networks)
      for (const auto& st : n.stages) history(st.summary, n.axis + " " + st.mode + " ");
  } else {
    history(r.training, "");
  }
  if (!loss.empty()) {
    b.page.figure(svg_line_chart(loss, {"training history of " + r.experiment, "epoch",
                                        "loss (normalised MSE)", true}),
                  "loss per epoch: " + file.filename().string());
  }
}

void add_run(Builder& b, const fs::path& file, int level) {
  if (first_showing(b, file)) add_run(b, file, read_result(file), level);
}

void add_study(Builder& b, const TableEntry& entry, const ReportOptions& o) {
  b.page.heading(2, "Study " + entry.name + ": " + entry.summary, entry.name);
  TablesOptions t = o.tables;
  t.format = TableFormat::markdown;
  std::ostringstream md;
  const LoadedTables loaded = load_tables(entry, t);
  loaded.print(md);
  std::istringstream in(md.str());
  TextTable table;
  std::string caption;
  std::vector<fs::path> sources;
  const auto flush = [&] {
    if (table.header.empty()) return;
    b.page.table(table, caption);
    table = {};
    caption.clear();
  };
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("|", 0) == 0) {
      auto cells = markdown_cells(line);
      if (table.header.empty()) {
        table.header = std::move(cells);
      } else if (!std::all_of(line.begin(), line.end(), [](char c) {
                   return c == '|' || c == '-' || c == ':' || c == ' ';
                 })) {
        cells.resize(table.header.size());
        table.rows.push_back(std::move(cells));
      }
      continue;
    }
    flush();
    if (line.rfind("#", 0) == 0) {
      caption = line.substr(line.find_first_not_of("# "));
      continue;
    }
    std::string text = line.rfind("- ", 0) == 0 ? line.substr(2) : line;
    if (text.empty()) continue;
    if (text.rfind("sources: ", 0) == 0) {
      std::istringstream list(text.substr(9));
      for (std::string f; std::getline(list, f, ',');) {
        f.erase(0, f.find_first_not_of(' '));
        if (fs::path(f).extension() == ".h5") sources.emplace_back(f);
      }
    }
    b.page.paragraph(text, "note");
  }
  flush();
  if (entry.measure && !entry.manifest.empty()) {
    const fs::path manifest = t.config_file(entry.manifest);
    const auto targets = read_targets(manifest);
    const auto results = check_targets(targets, loaded.measure(), t.profile);
    TextTable check;
    check.header = {"quantity", "target", "measured", "result", "source"};
    for (const auto& r : results) {
      const std::string verdict = !r.wanted ? "not checked" : (r.pass ? "PASS" : "FAIL");
      if (r.wanted && !r.pass) ++b.failed_targets;
      check.rows.push_back(
          {r.target->name,
           r.wanted ? std::string(to_string(r.target->op)) + " " + shortest_double(*r.wanted)
                    : "(not declared for this profile)",
           format_metric(r.measured), verdict, r.target->source});
    }
    b.page.table(check, "declared targets (" + manifest.filename().string() + ")");
  }
  StudyFigureOptions figures;
  figures.figures_dir = t.results_dir / "figures";
  figures.topics = entry.figure_topics;
  figures.anchor = "figures-" + entry.name;
  figures.draw_command = "bash scripts/figures/run " + t.results_dir.string();
  for (const auto& f : sources) {
    std::error_code ec;
    const auto time = fs::last_write_time(f, ec);
    if (!ec && (!figures.newest_source || time > *figures.newest_source))
      figures.newest_source = time;
  }
  add_study_figures(b.page, figures);
  if (!sources.empty()) b.page.heading(3, "Runs behind these numbers", "");
  std::vector<fs::path> unseen;
  for (const auto& f : sources) {
    if (first_showing(b, f)) unseen.push_back(f);
  }
  std::vector<ReadOutcome<RunRecord>> records = read_results(unseen);  // one isolated child
  for (std::size_t i = 0; i < unseen.size(); ++i) {
    add_run(b, unseen[i], std::move(records[i]).get(), 4);
  }
}

void add_sweep(Builder& b, const fs::path& dir) {
  const SweepPlan plan = load_plan(dir);
  const auto outcomes = read_trial_outcomes(dir, plan);
  const SweepSummary s = summarize(plan, outcomes);
  const std::string& objective = plan.objective.metric;
  b.page.heading(2, "Sweep of " + plan.experiment + " (" + dir.filename().string() + ")", "");
  b.page.paragraph(std::to_string(plan.trials.size()) + " trials (" + std::to_string(s.complete) +
                   " complete, " + std::to_string(s.failed + s.errors) + " failed, " +
                   std::to_string(s.missing) + " not run); objective " + objective + " (" +
                   (plan.objective.maximize ? "max" : "min") + "), mean over repeats");
  TextTable rank;
  rank.header = {"rank"};
  for (const auto& k : plan.keys) rank.header.push_back(k);
  rank.header.insert(rank.header.end(), {objective + " mean", "std", "complete"});
  std::vector<std::vector<std::string>> lines;
  std::size_t n = 0;
  for (const auto& p : s.points) {
    std::vector<std::string> row = {std::to_string(++n)};
    row.insert(row.end(), p.values.begin(), p.values.end());
    const auto m = p.mean.find(objective), sd = p.std.find(objective);
    row.push_back(m == p.mean.end() ? "—" : format_metric(m->second));
    const bool spread = sd != p.std.end() && std::isfinite(sd->second);  // one repeat: none
    row.push_back(spread ? format_metric(sd->second) : "—");
    row.push_back(std::to_string(p.complete) + "/" + std::to_string(p.trials.size()));
    rank.rows.push_back(row);
    std::vector<std::string> line = p.values;
    line.push_back(m == p.mean.end() ? "" : shortest_double(m->second));
    lines.push_back(std::move(line));
  }
  b.page.table(rank, "ranking, best first");
  std::vector<std::string> axes = plan.keys;
  axes.push_back(objective);
  b.page.figure(svg_parallel_coordinates(axes, lines, "parallel coordinates: " + plan.experiment),
                "one line per point, the best in red; the last axis is the objective");
  add_parameter_importance(b.page, dir / "summary.h5");
  if (s.best_trial >= 0) {
    const auto& best = outcomes[static_cast<std::size_t>(s.best_trial)];
    if (!best.result_file.empty()) add_run(b, dir / best.result_file, 3);
  }
}

}  // namespace

Report build_report(const ReportOptions& o) {
  std::string title = "cnclab report:";
  for (const auto& i : o.inputs) title.append(" ").append(fs::path(i).filename().string());
  Builder b{HtmlPage(title), 0, {}};
  b.page.heading(1, title, "");
  b.page.paragraph("Made by cnclab " + make_provenance(0).cnclab_version + " on " +
                       utc_now_iso8601() +
                       (o.tables.profile.empty() ? "" : ", profile " + o.tables.profile) +
                       ". Every number comes from the result file named beside it.",
                   "note");
  for (const auto& input : o.inputs) {
    std::error_code ec;
    const auto& tables = registered_tables();
    const auto study = std::find_if(tables.begin(), tables.end(),
                                    [&](const TableEntry& e) { return e.name == input; });
    if (study != tables.end()) {
      add_study(b, *study, o);
    } else if (fs::is_directory(input, ec) && fs::exists(fs::path(input) / "sweep.yaml", ec)) {
      add_sweep(b, input);
    } else if (fs::is_regular_file(input, ec)) {
      b.page.heading(2, "Result " + fs::path(input).filename().string(), "");
      add_run(b, input, 3);
    } else {
      std::string names;
      for (const auto& e : tables) names += (names.empty() ? "" : ", ") + e.name;
      throw ConfigError("report: '" + input + "' is no study (" + names +
                        "), sweep folder or result file");
    }
  }
  return {b.page.html(), b.failed_targets};
}

int report_command(const ReportOptions& o, std::ostream& out) {
  if (o.output.extension() != ".html") {
    throw ConfigError("report -o " + o.output.string() + ": the file must end in .html");
  }
  const Report r = build_report(o);
  write_text_atomically(o.output, r.html);
  out << o.output.string() << " (" << (r.html.size() + 512) / 1024 << " kB";
  if (r.failed_targets) out << ", " << r.failed_targets << " declared target(s) FAIL";
  out << ")\n";
  return r.failed_targets ? 1 : 0;
}

}  // namespace cnclab
