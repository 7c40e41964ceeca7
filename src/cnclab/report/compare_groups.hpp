#pragma once
// `cnclab compare --group-by KEY`: runs grouped by a config key (or the
// repeats of one config), compared only where nothing else differs.
//
// Strata. Other config keys may vary inside the groups: a sweep over
// dropout × learning rate grouped by dropout holds every learning rate in
// each group, and comparing such groups mixes the learning rate's effect into
// the dropout's. So the keys that vary inside some group (the seed aside: it
// is the replicate) define strata, one per combination of their values, and
// the groups are compared within each stratum. Keys constant in every group
// but different between groups go with the grouping (trainer.learning_rate
// beside trainer.type) and are named. `pool` compares across the strata
// instead, and the output names the pooled keys.
//
// Per stratum, each metric as mean with its Student-t interval over the
// group's runs, clipped to the metric's possible range (nn/metric_range.hpp;
// ci_clipped names the bounds that were), and each later group against the
// stratum's first group: the difference of means, Welch's t-test (two-sided
// p) and a percentile bootstrap interval of the difference (statistics.hpp;
// it lies within the data, so within the range). Runs of the two groups
// with the same seed (and, pooled, the same values of the pooled keys) form
// pairs; with two or more, the paired t-test and the Wilcoxon signed-rank
// test over them too. `significant` comes from the paired t-test when every
// run of both groups is in a pair (the design is paired), else from Welch's
// (`test` says which); "no" when p is not below alpha. No correction for
// several comparisons: with k groups in a stratum, k - 1 tests at alpha each.
//
// One row per (metric, stratum, group) with the same columns in every
// format (the difference columns empty for a stratum's first group;
// intervals at level 1 - alpha).
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/report/compare.hpp"
#include "cnclab/report/statistics.hpp"

namespace cnclab {

// KEY that groups the repeats of each config: runs whose resolved configs
// are equal apart from `seed` (sweep --repeats, a seed list).
inline constexpr const char* kGroupRepeats = "repeats";

struct GroupCompareOptions {
  std::string group_by;           // a dotted config key (trainer.type) or kGroupRepeats
  double alpha = 0.05;            // significance level; intervals at 1 - alpha. In (0, 0.5]
  std::size_t resamples = 10000;  // bootstrap resamples (>= 100)
  std::uint64_t seed = 20260212;  // bootstrap seed: same runs, same intervals
  bool pool = false;              // compare across the other varying keys (named in the output)
  bool full = false;              // arrays in labels in full (else shape and hash, as `show`)
  void validate() const;          // OptionError naming the field
};

struct RunGroup {
  std::string label;              // "trainer.type=NAME", or the repeats' distinguishing keys
  std::vector<std::size_t> runs;  // indices into the runs, in input order
};

// Groups in order of first appearance. ConfigError when no run has the key
// (with "did you mean" over the runs' keys) or fewer than two groups result.
std::vector<RunGroup> group_runs(const std::vector<ComparedRun>& runs, const std::string& group_by,
                                 bool full = false);

struct Stratum {
  std::string label;             // "trainer.momentum=0.9 trainer.learning_rate=0.01"; "all runs"
  std::vector<RunGroup> groups;  // the groups with runs here, their runs restricted to it
};

struct GroupDesign {
  std::vector<RunGroup> groups;          // over all runs (group_runs)
  std::vector<std::string> varying;      // keys varying inside a group: strata or pooled
  std::vector<std::string> with_groups;  // constant in each group, different between groups
  bool pooled = false;                   // options.pool and something varies
  std::vector<Stratum> strata;           // one, "all runs", when pooled or nothing varies
};
GroupDesign design_groups(const std::vector<ComparedRun>& runs, const GroupCompareOptions& options);

struct GroupRow {
  std::string metric, stratum, group;
  SampleSummary summary;    // over the group's finite values, interval clipped to the range
  std::string ci_clipped;   // "low", "high", "both" or "": the bounds clipped to the range
  bool reference = false;   // the stratum's first group: no difference columns
  WelchTest welch;          // group - first group
  Interval bootstrap;       // of group - first group
  PairedTTest paired;       // over the pairs (pairs = 0: none)
  WilcoxonTest wilcoxon;    // over the same pairs
  std::string test;         // what `significant` uses: "paired t" or "welch"
  std::string significant;  // "yes", "no", or "n/a" (test undefined); "" for the reference
};

// Every metric any run has, for every group of every stratum.
std::vector<GroupRow> compare_groups(const std::vector<ComparedRun>& runs,
                                     const GroupDesign& design, const GroupCompareOptions& options);

void print_group_comparison(const std::vector<ComparedRun>& runs,
                            const GroupCompareOptions& options, CompareFormat format,
                            std::ostream& out);

// collect_runs (compare.hpp), then print_group_comparison. Returns 0.
int compare_groups_command(const std::vector<std::string>& inputs, const std::string& format,
                           const GroupCompareOptions& options, std::ostream& out);

}  // namespace cnclab
