#include "cnclab/report/compare_groups.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/suggest.hpp"
#include "cnclab/experiment/sequence_metrics.hpp"
#include "cnclab/nn/metric_range.hpp"
#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace {

// Keys a repeat may differ in: the master seed (sweep --repeats, seed lists).
bool is_seed_key(const std::string& key) {
  return key == "seed";
}

using FlatConfig = std::map<std::string, std::string>;

FlatConfig flat(const ComparedRun& r, bool full) {
  FlatConfig out;
  for (auto& [k, v] : flatten_config(r.record.resolved_yaml, full)) out[k] = v;
  return out;
}

// A key's value in a config, kMissingCell when the config lacks it.
std::string value_of(const FlatConfig& c, const std::string& key) {
  const auto it = c.find(key);
  return it == c.end() ? kMissingCell : it->second;
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
      const std::string mine = value_of(keys_of[g], k);
      const bool differs = std::any_of(keys_of.begin(), keys_of.end(),
                                       [&](const FlatConfig& o) { return value_of(o, k) != mine; });
      if (differs) label += (label.empty() ? "" : " ") + k + "=" + mine;
    }
    groups[g].label = label.empty() ? "group " + std::to_string(g + 1) : label;
  }
  return groups;
}

std::vector<RunGroup> group_by_key(const std::vector<FlatConfig>& configs, const std::string& key) {
  std::vector<RunGroup> groups;
  bool any = false;
  for (std::size_t i = 0; i < configs.size(); ++i) {
    any = any || configs[i].count(key) > 0;
    const std::string label = key + "=" + value_of(configs[i], key);
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

std::vector<FlatConfig> flat_configs(const std::vector<ComparedRun>& runs, bool full) {
  std::vector<FlatConfig> configs;
  for (const auto& r : runs) configs.push_back(flat(r, full));
  return configs;
}

// The keys other than the grouping key and the seed, split into those that
// vary inside some group and those constant in each group that differ
// between groups.
void classify_keys(const std::vector<FlatConfig>& configs, const std::vector<RunGroup>& groups,
                   const std::string& group_by, GroupDesign& d) {
  std::set<std::string> keys;
  for (const auto& c : configs) {
    for (const auto& [k, v] : c) {
      if (k != group_by && !is_seed_key(k)) keys.insert(k);
    }
  }
  for (const auto& k : keys) {
    bool inside = false;
    std::set<std::string> per_group;
    for (const auto& g : groups) {
      std::set<std::string> values;
      for (std::size_t i : g.runs) values.insert(value_of(configs[i], k));
      inside = inside || values.size() > 1;
      per_group.insert(*values.begin());
    }
    if (inside) {
      d.varying.push_back(k);
    } else if (per_group.size() > 1) {
      d.with_groups.push_back(k);
    }
  }
}

// One stratum per combination of the varying keys' values (order of first
// appearance), each with the groups that have runs in it.
std::vector<Stratum> stratify(const std::vector<FlatConfig>& configs, const GroupDesign& d) {
  std::vector<std::vector<std::string>> combos;
  std::vector<Stratum> strata;
  const bool split = !d.pooled && !d.varying.empty();
  for (std::size_t g = 0; g < d.groups.size(); ++g) {
    for (std::size_t i : d.groups[g].runs) {
      std::vector<std::string> combo;
      if (split) {
        for (const auto& k : d.varying) combo.push_back(value_of(configs[i], k));
      }
      auto it = std::find(combos.begin(), combos.end(), combo);
      if (it == combos.end()) {
        combos.push_back(combo);
        std::string label;
        for (std::size_t k = 0; k < combo.size(); ++k) {
          label += (k ? " " : "") + d.varying[k] + "=" + combo[k];
        }
        strata.push_back({label.empty() ? "all runs" : label, {}});
        it = combos.end() - 1;
      }
      Stratum& s = strata[static_cast<std::size_t>(it - combos.begin())];
      if (s.groups.empty() || s.groups.back().label != d.groups[g].label) {
        s.groups.push_back({d.groups[g].label, {}});
      }
      s.groups.back().runs.push_back(i);
    }
  }
  // Groups in their global order within each stratum (runs were visited
  // group by group, so they already are).
  return strata;
}

// The metric's possible range: a registered sequence metric's, else the
// regression metrics' (nn/metric_range.hpp); unbounded for others.
MetricRange range_of(const std::string& metric) {
  const MetricRange r = sequence_metric_range(metric);
  return r.bounded() ? r : metric_range(metric);
}

// The interval of `s` clipped to `range`; which bounds were.
std::string clip(SampleSummary& s, const MetricRange& range) {
  const bool low = s.ci_low<range.low, high = s.ci_high> range.high;
  if (low) s.ci_low = range.low;
  if (high) s.ci_high = range.high;
  return low && high ? "both" : low ? "low" : high ? "high" : "";
}

// What pairs run i with a run of another group: its seed and its values of
// the varying keys (constant within a stratum; pooled, they tell the runs apart).
std::string pair_key(const FlatConfig& c, const GroupDesign& d) {
  std::string key = value_of(c, "seed");
  for (const auto& k : d.varying) {
    key += '\n';  // appended: GCC 12 warns falsely on "\n" + std::string (-Wrestrict, PR105329)
    key += value_of(c, k);
  }
  return key;
}

// Finite values of `metric` per pair key of the group's runs; keys that occur
// more than once in the group are left out (they cannot pair).
std::map<std::string, double> keyed_values(const std::vector<ComparedRun>& runs,
                                           const std::vector<FlatConfig>& configs,
                                           const RunGroup& g, const GroupDesign& d,
                                           const std::string& metric) {
  std::map<std::string, double> out;
  std::set<std::string> repeated;
  for (std::size_t i : g.runs) {
    const auto it = runs[i].record.metrics.find(metric);
    if (it == runs[i].record.metrics.end() || !std::isfinite(it->second)) continue;
    const std::string key = pair_key(configs[i], d);
    if (!out.emplace(key, it->second).second) repeated.insert(key);
  }
  for (const auto& k : repeated) out.erase(k);
  return out;
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

// Group g of a stratum against its first group.
void compare_with_first(const std::vector<ComparedRun>& runs,
                        const std::vector<FlatConfig>& configs, const GroupDesign& d,
                        const Stratum& s, std::size_t g, const GroupCompareOptions& o,
                        GroupRow& row) {
  BootstrapOptions boot;
  boot.resamples = o.resamples;
  boot.seed = o.seed;
  boot.level = 1 - o.alpha;
  const std::vector<double> first = values_of(runs, s.groups.front(), row.metric);
  const std::vector<double> mine = values_of(runs, s.groups[g], row.metric);
  row.welch = welch_t_test(first, mine);
  row.bootstrap = bootstrap_difference_ci(first, mine, boot);
  const auto a = keyed_values(runs, configs, s.groups.front(), d, row.metric);
  const auto b = keyed_values(runs, configs, s.groups[g], d, row.metric);
  std::vector<double> pa, pb;
  for (const auto& [key, v] : a) {
    if (const auto it = b.find(key); it != b.end()) {
      pa.push_back(v);
      pb.push_back(it->second);
    }
  }
  row.paired = paired_t_test(pa, pb);
  row.wilcoxon = wilcoxon_signed_rank(pa, pb);
  if (pa.size() < 2) row.wilcoxon = {pa.size(), NAN, NAN, false};
  const bool all_paired = pa.size() >= 2 && pa.size() == first.size() && pa.size() == mine.size();
  row.test = all_paired ? "paired t" : "welch";
  const double p = all_paired ? row.paired.p_value : row.welch.p_value;
  row.significant = std::isnan(p) ? "n/a" : p < o.alpha ? "yes" : "no";
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

std::vector<RunGroup> group_runs(const std::vector<ComparedRun>& runs, const std::string& group_by,
                                 bool full) {
  const std::vector<FlatConfig> configs = flat_configs(runs, full);
  std::vector<RunGroup> groups =
      group_by == kGroupRepeats ? group_repeats(configs) : group_by_key(configs, group_by);
  if (groups.size() < 2) {
    throw ConfigError("compare --group-by " + group_by + ": all " + std::to_string(runs.size()) +
                      " runs fall in one group (" + groups.front().label + "); nothing to compare");
  }
  return groups;
}

GroupDesign design_groups(const std::vector<ComparedRun>& runs, const GroupCompareOptions& o) {
  GroupDesign d;
  d.groups = group_runs(runs, o.group_by, o.full);
  const std::vector<FlatConfig> configs = flat_configs(runs, o.full);
  if (o.group_by != kGroupRepeats) classify_keys(configs, d.groups, o.group_by, d);
  d.pooled = o.pool && !d.varying.empty();
  d.strata = stratify(configs, d);
  return d;
}

std::vector<GroupRow> compare_groups(const std::vector<ComparedRun>& runs, const GroupDesign& d,
                                     const GroupCompareOptions& o) {
  o.validate();
  const std::vector<FlatConfig> configs = flat_configs(runs, o.full);
  std::set<std::string> metrics;
  for (const auto& r : runs) {
    for (const auto& [name, v] : r.record.metrics) metrics.insert(name);
  }
  std::vector<GroupRow> rows;
  for (const auto& m : metrics) {
    const MetricRange range = range_of(m);
    for (const auto& s : d.strata) {
      for (std::size_t g = 0; g < s.groups.size(); ++g) {
        GroupRow row;
        row.metric = m;
        row.stratum = s.label;
        row.group = s.groups[g].label;
        row.summary = summarize(values_of(runs, s.groups[g], m), 1 - o.alpha);
        row.ci_clipped = clip(row.summary, range);
        row.reference = g == 0;
        if (!row.reference) compare_with_first(runs, configs, d, s, g, o, row);
        rows.push_back(std::move(row));
      }
    }
  }
  return rows;
}

int compare_groups_command(const std::vector<std::string>& inputs, const std::string& format,
                           const GroupCompareOptions& options, std::ostream& out) {
  const CompareFormat f = parse_compare_format(format);
  options.validate();
  print_group_comparison(collect_runs(inputs), options, f, out);
  return 0;
}

}  // namespace cnclab
