#include "cnclab/report/compare_groups.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/suggest.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace {

// Keys a repeat may differ in: the master seed (sweep --repeats, seed lists).
bool is_seed_key(const std::string& key) {
  return key == "seed";
}

using FlatConfig = std::map<std::string, std::string>;

FlatConfig flat(const ComparedRun& r) {
  FlatConfig out;
  for (auto& [k, v] : flatten_config(r.record.resolved_yaml)) out[k] = v;
  return out;
}

// Groups of runs with equal configs apart from seed; each labelled with the
// keys whose values differ between the groups ("model.hidden=[8]").
std::vector<RunGroup> group_repeats(const std::vector<FlatConfig>& configs) {
  std::vector<RunGroup> groups;
  std::vector<FlatConfig> keys_of;  // each group's config without the seed
  for (std::size_t i = 0; i < configs.size(); ++i) {
    FlatConfig c = configs[i];
    std::erase_if(c, [](const auto& kv) { return is_seed_key(kv.first); });
    const auto it = std::find(keys_of.begin(), keys_of.end(), c);
    if (it == keys_of.end()) {
      keys_of.push_back(std::move(c));
      groups.push_back({"", {i}});
    } else {
      groups[static_cast<std::size_t>(it - keys_of.begin())].runs.push_back(i);
    }
  }
  std::set<std::string> all;
  for (const auto& c : keys_of) {
    for (const auto& [k, v] : c) all.insert(k);
  }
  for (std::size_t g = 0; g < groups.size(); ++g) {
    std::string label;
    for (const auto& k : all) {
      const auto mine = keys_of[g].find(k);
      const bool differs = std::any_of(keys_of.begin(), keys_of.end(), [&](const FlatConfig& o) {
        const auto theirs = o.find(k);
        return (theirs == o.end()) != (mine == keys_of[g].end()) ||
               (theirs != o.end() && theirs->second != mine->second);
      });
      if (differs) {
        label += (label.empty() ? "" : " ") + k + "=" +
                 (mine == keys_of[g].end() ? kMissingCell : mine->second);
      }
    }
    groups[g].label = label.empty() ? "group " + std::to_string(g + 1) : label;
  }
  return groups;
}

std::vector<RunGroup> group_by_key(const std::vector<FlatConfig>& configs, const std::string& key) {
  std::vector<RunGroup> groups;
  bool any = false;
  for (std::size_t i = 0; i < configs.size(); ++i) {
    const auto it = configs[i].find(key);
    any = any || it != configs[i].end();
    const std::string label = key + "=" + (it == configs[i].end() ? kMissingCell : it->second);
    const auto g = std::find_if(groups.begin(), groups.end(),
                                [&](const RunGroup& x) { return x.label == label; });
    if (g == groups.end()) {
      groups.push_back({label, {i}});
    } else {
      g->runs.push_back(i);
    }
  }
  if (!any) {
    std::set<std::string> names;
    for (const auto& c : configs) {
      for (const auto& [k, v] : c) names.insert(k);
    }
    throw ConfigError("compare --group-by " + key + ": no run has this config key" +
                      did_you_mean(key, {names.begin(), names.end()}) + " (or --group-by " +
                      kGroupRepeats + ": the repeats of each config)");
  }
  return groups;
}

// The group's finite values of `metric` (a diverged run's NaN is left out).
std::vector<double> values_of(const std::vector<ComparedRun>& runs, const RunGroup& g,
                              const std::string& metric) {
  std::vector<double> v;
  for (std::size_t i : g.runs) {
    const auto it = runs[i].record.metrics.find(metric);
    if (it != runs[i].record.metrics.end() && std::isfinite(it->second)) v.push_back(it->second);
  }
  return v;
}

const std::vector<std::string> kColumns = {"metric",  "group",    "n",         "mean",       "std",
                                           "ci_low",  "ci_high",  "diff",      "welch_t",    "df",
                                           "p_value", "boot_low", "boot_high", "significant"};

// A row's cells in kColumns order; NaN and the reference group's difference
// columns as "" (numbers at full precision: csv and json are for programs).
std::vector<std::string> cells(const GroupRow& r, bool display) {
  const auto num = [&](double v) -> std::string {
    if (std::isnan(v)) return display ? "-" : "";
    return display ? format_metric(v) : shortest_double(v);
  };
  std::vector<std::string> c = {r.metric,
                                r.group,
                                std::to_string(r.summary.n),
                                num(r.summary.mean),
                                num(r.summary.std),
                                num(r.summary.ci_low),
                                num(r.summary.ci_high)};
  if (r.reference) {
    c.resize(kColumns.size() - 1, "");
    c.push_back("");
    return c;
  }
  for (double v : {r.welch.difference, r.welch.t, r.welch.df, r.welch.p_value, r.bootstrap.low,
                   r.bootstrap.high}) {
    c.push_back(num(v));
  }
  c.push_back(r.significant);
  return c;
}

void print_json(const std::vector<ComparedRun>& runs, const std::vector<RunGroup>& groups,
                const std::vector<GroupRow>& rows, const GroupCompareOptions& o,
                std::ostream& out) {
  using Json = nlohmann::ordered_json;
  Json doc;
  doc["group_by"] = o.group_by;
  doc["alpha"] = o.alpha;
  doc["level"] = 1 - o.alpha;
  doc["bootstrap"] = {{"resamples", o.resamples}, {"seed", o.seed}, {"method", "percentile"}};
  doc["groups"] = Json::array();
  for (const auto& g : groups) {
    Json files = Json::array();
    for (std::size_t i : g.runs) files.push_back(runs[i].file.string());
    doc["groups"].push_back({{"label", g.label}, {"runs", files}});
  }
  doc["columns"] = kColumns;
  doc["rows"] = Json::array();
  for (const auto& r : rows) {
    const std::vector<std::string> c = cells(r, false);
    Json row;
    for (std::size_t k = 0; k < kColumns.size(); ++k) {
      const bool text = k < 2 || kColumns[k] == "significant";
      if (text) {
        row[kColumns[k]] = c[k];
      } else if (kColumns[k] == "n") {
        row["n"] = r.summary.n;  // a count, not 2.0
      } else if (c[k].empty()) {
        row[kColumns[k]] = nullptr;  // NaN, or the reference group's difference
      } else {
        row[kColumns[k]] = std::stod(c[k]);
      }
    }
    doc["rows"].push_back(std::move(row));
  }
  out << doc.dump(2) << "\n";
}

}  // namespace

void GroupCompareOptions::validate() const {
  if (group_by.empty()) throw OptionError("group_by", "\"\"", "must name a config key");
  if (!(alpha > 0 && alpha <= 0.5)) {
    throw OptionError("alpha", shortest_double(alpha), "must be in (0, 0.5]");
  }
  BootstrapOptions b;
  b.resamples = resamples;
  b.validate();
}

std::vector<RunGroup> group_runs(const std::vector<ComparedRun>& runs,
                                 const std::string& group_by) {
  std::vector<FlatConfig> configs;
  for (const auto& r : runs) configs.push_back(flat(r));
  std::vector<RunGroup> groups =
      group_by == kGroupRepeats ? group_repeats(configs) : group_by_key(configs, group_by);
  if (groups.size() < 2) {
    throw ConfigError("compare --group-by " + group_by + ": all " + std::to_string(runs.size()) +
                      " runs fall in one group (" + groups.front().label + "); nothing to compare");
  }
  return groups;
}

std::vector<GroupRow> compare_groups(const std::vector<ComparedRun>& runs,
                                     const std::vector<RunGroup>& groups,
                                     const GroupCompareOptions& o) {
  o.validate();
  BootstrapOptions boot;
  boot.resamples = o.resamples;
  boot.seed = o.seed;
  boot.level = 1 - o.alpha;
  std::set<std::string> metrics;
  for (const auto& r : runs) {
    for (const auto& [name, v] : r.record.metrics) metrics.insert(name);
  }
  std::vector<GroupRow> rows;
  for (const auto& m : metrics) {
    const std::vector<double> first = values_of(runs, groups.front(), m);
    for (std::size_t g = 0; g < groups.size(); ++g) {
      GroupRow row;
      row.metric = m;
      row.group = groups[g].label;
      const std::vector<double> v = values_of(runs, groups[g], m);
      row.summary = summarize(v, 1 - o.alpha);
      row.reference = g == 0;
      if (!row.reference) {
        row.welch = welch_t_test(first, v);
        row.bootstrap = bootstrap_difference_ci(first, v, boot);
        row.significant = std::isnan(row.welch.p_value) ? "n/a"
                          : row.welch.p_value < o.alpha ? "yes"
                                                        : "no";
      }
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

void print_group_comparison(const std::vector<ComparedRun>& runs, const GroupCompareOptions& o,
                            CompareFormat format, std::ostream& out) {
  const std::vector<RunGroup> groups = group_runs(runs, o.group_by);
  const std::vector<GroupRow> rows = compare_groups(runs, groups, o);
  if (format == CompareFormat::json) {
    print_json(runs, groups, rows, o, out);
    return;
  }
  TextTable t;
  t.header = kColumns;
  const bool display = format == CompareFormat::table || format == CompareFormat::markdown;
  for (const auto& r : rows) t.rows.push_back(cells(r, display));
  if (format == CompareFormat::csv) {
    t.print_csv(out);
    return;
  }
  const bool md = format == CompareFormat::markdown;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    out << (md ? "- " : "") << "group " << g + 1 << ": " << groups[g].label << " ("
        << groups[g].runs.size() << " run(s))\n";
  }
  out << "\n";
  if (md) {
    t.print_markdown(out);
  } else {
    t.print_aligned(out);
  }
  const std::string level = shortest_double(100 * (1 - o.alpha));
  out << "\nmean with its " << level << " % Student-t interval [ci_low, ci_high] over each "
      << "group's runs; diff = mean - the first group's mean, Welch's t-test (two-sided p, "
      << "Welch-Satterthwaite df) and a " << level << " % percentile bootstrap interval of the "
      << "difference (" << o.resamples << " resamples, seed " << o.seed << "); significant: p < "
      << shortest_double(o.alpha) << " (no correction for " << groups.size() - 1
      << " comparison(s) per metric)\n";
}

int compare_groups_command(const std::vector<std::string>& inputs, const std::string& format,
                           const GroupCompareOptions& options, std::ostream& out) {
  const CompareFormat f = parse_compare_format(format);
  options.validate();
  print_group_comparison(collect_runs(inputs), options, f, out);
  return 0;
}

}  // namespace cnclab
