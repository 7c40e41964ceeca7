// print_group_comparison (compare_groups.hpp): the design (groups, strata or
// pooled keys), the rows in every format and the note on the methods.
#include <cmath>
#include <nlohmann/json.hpp>

#include "cnclab/core/format.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/report/compare_groups.hpp"
#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace {

const std::vector<std::string> kColumns = {
    "metric",     "stratum",    "group",      "n",          "mean",     "std",
    "ci_low",     "ci_high",    "ci_clipped", "diff",       "welch_t",  "welch_df",
    "welch_p",    "boot_low",   "boot_high",  "pairs",      "paired_t", "paired_p",
    "wilcoxon_w", "wilcoxon_p", "test",       "significant"};

// Columns holding text, and counts, in csv and json.
bool text_column(const std::string& c) {
  return c == "metric" || c == "stratum" || c == "group" || c == "ci_clipped" || c == "test" ||
         c == "significant";
}
bool count_column(const std::string& c) {
  return c == "n" || c == "pairs";
}

// A row's cells in kColumns order: NaN and a reference row's difference
// columns empty ("-" for NaN in the display); numbers at full precision in
// csv and json. `stratum`: the stratum's text in that column.
std::vector<std::string> cells(const GroupRow& r, bool display, const std::string& stratum) {
  const auto num = [&](double v) -> std::string {
    if (std::isnan(v)) return display ? "-" : "";
    return display ? format_metric(v) : shortest_double(v);
  };
  std::vector<std::string> c = {r.metric,
                                stratum,
                                r.group,
                                std::to_string(r.summary.n),
                                num(r.summary.mean),
                                num(r.summary.std),
                                num(r.summary.ci_low),
                                num(r.summary.ci_high),
                                r.ci_clipped};
  if (r.reference) {
    c.resize(kColumns.size(), "");
    return c;
  }
  for (double v : {r.welch.difference, r.welch.t, r.welch.df, r.welch.p_value, r.bootstrap.low,
                   r.bootstrap.high}) {
    c.push_back(num(v));
  }
  c.push_back(std::to_string(r.paired.pairs));
  for (double v : {r.paired.t, r.paired.p_value, r.wilcoxon.w, r.wilcoxon.p_value}) {
    c.push_back(num(v));
  }
  c.push_back(r.test);
  c.push_back(r.significant);
  return c;
}

std::string join(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ", ") + i;
  return s;
}

void print_json(const std::vector<ComparedRun>& runs, const GroupDesign& d,
                const std::vector<GroupRow>& rows, const GroupCompareOptions& o,
                std::ostream& out) {
  using Json = nlohmann::ordered_json;
  const auto groups_json = [&](const std::vector<RunGroup>& groups) {
    Json list = Json::array();
    for (const auto& g : groups) {
      Json files = Json::array();
      for (std::size_t i : g.runs) files.push_back(runs[i].file.string());
      list.push_back({{"label", g.label}, {"runs", files}});
    }
    return list;
  };
  Json doc;
  doc["group_by"] = o.group_by;
  doc["alpha"] = o.alpha;
  doc["level"] = 1 - o.alpha;
  doc["bootstrap"] = {{"resamples", o.resamples}, {"seed", o.seed}, {"method", "percentile"}};
  doc["groups"] = groups_json(d.groups);
  // The keys that vary inside the groups: the strata's, or pooled.
  doc["varying_keys"] = d.varying;
  doc["pooled"] = d.pooled;
  doc["with_groups"] = d.with_groups;
  doc["strata"] = Json::array();
  for (const auto& s : d.strata) {
    doc["strata"].push_back({{"label", s.label}, {"groups", groups_json(s.groups)}});
  }
  doc["columns"] = kColumns;
  doc["rows"] = Json::array();
  for (const auto& r : rows) {
    const std::vector<std::string> c = cells(r, false, r.stratum);
    Json row;
    for (std::size_t k = 0; k < kColumns.size(); ++k) {
      const std::string& name = kColumns[k];
      if (text_column(name)) {
        row[name] = c[k];
      } else if (c[k].empty()) {
        row[name] = nullptr;  // NaN, or the reference group's difference
      } else if (count_column(name)) {
        row[name] = std::stoull(c[k]);  // a count, not 2.0
      } else {
        row[name] = std::stod(c[k]);
      }
    }
    doc["rows"].push_back(std::move(row));
  }
  out << doc.dump(2) << "\n";
}

// The design for people: groups, then what varies inside them and how it is
// handled, then the strata that compare nothing.
void print_design(const GroupDesign& d, bool md, std::ostream& out) {
  const std::string item = md ? "- " : "";
  for (std::size_t g = 0; g < d.groups.size(); ++g) {
    out << item << "group " << g + 1 << ": " << d.groups[g].label << " (" << d.groups[g].runs.size()
        << " run(s))\n";
  }
  if (!d.with_groups.empty()) {
    out << item << "differing with the groups (constant in each): " << join(d.with_groups) << "\n";
  }
  if (d.pooled) {
    out << item << "POOLED over " << join(d.varying)
        << " (--pool): each group mixes runs that differ in these keys too\n";
  } else if (!d.varying.empty()) {
    out << item << "varying inside the groups: " << join(d.varying)
        << "; compared within each combination of them (--pool compares across them):\n";
    for (std::size_t s = 0; s < d.strata.size(); ++s) {
      std::size_t n = 0;
      for (const auto& g : d.strata[s].groups) n += g.runs.size();
      out << item << "stratum " << s + 1 << ": " << d.strata[s].label << " ("
          << d.strata[s].groups.size() << " group(s), " << n << " run(s))\n";
    }
  }
  bool compared = false;
  for (std::size_t s = 0; s < d.strata.size(); ++s) {
    compared = compared || d.strata[s].groups.size() > 1;
    if (d.strata[s].groups.size() == 1 && d.strata.size() > 1) {
      out << item << "stratum " << s + 1 << " holds only " << d.strata[s].groups[0].label
          << ": nothing compared there\n";
    }
  }
  if (!compared) {
    out << item << "no stratum holds two groups: the groups differ in the varying keys too; "
        << "--pool compares across them\n";
  }
  out << "\n";
}

}  // namespace

void print_group_comparison(const std::vector<ComparedRun>& runs, const GroupCompareOptions& o,
                            CompareFormat format, std::ostream& out) {
  const GroupDesign d = design_groups(runs, o);
  const std::vector<GroupRow> rows = compare_groups(runs, d, o);
  if (format == CompareFormat::json) {
    print_json(runs, d, rows, o, out);
    return;
  }
  TextTable t;
  t.header = kColumns;
  const bool display = format == CompareFormat::table || format == CompareFormat::markdown;
  for (const auto& r : rows) {
    // The display names a stratum by its number (listed above the table).
    std::string stratum = r.stratum;
    if (display) {
      for (std::size_t s = 0; s < d.strata.size(); ++s) {
        if (d.strata[s].label == r.stratum) stratum = std::to_string(s + 1);
      }
    }
    t.rows.push_back(cells(r, display, stratum));
  }
  if (format == CompareFormat::csv) {
    t.print_csv(out);
    return;
  }
  const bool md = format == CompareFormat::markdown;
  print_design(d, md, out);
  if (md) {
    t.print_markdown(out);
  } else {
    t.print_aligned(out);
  }
  std::size_t tests = 0;
  for (const auto& s : d.strata) tests += s.groups.size() - 1;
  const std::string level = shortest_double(100 * (1 - o.alpha));
  out << "\nmean with its " << level << " % Student-t interval [ci_low, ci_high] over each "
      << "group's runs, clipped to the metric's possible range (e.g. r2 <= 1, errors >= 0; "
      << "ci_clipped names the clipped bounds); diff = mean - the stratum's first group's mean, "
      << "Welch's t-test (two-sided p, Welch-Satterthwaite df) and a " << level
      << " % percentile bootstrap interval of the difference (" << o.resamples
      << " resamples, seed " << o.seed << "); runs with the same seed"
      << (d.pooled ? " and pooled values" : "") << " pair up: paired t-test and Wilcoxon "
      << "signed-rank test over the pairs (exact p for up to 50 pairs without ties, else the "
      << "normal approximation); significant: p < " << shortest_double(o.alpha)
      << " by the test in column test (paired t when every run is in a pair, else Welch); no "
      << "correction for " << tests << " comparison(s) per metric\n";
}

}  // namespace cnclab
