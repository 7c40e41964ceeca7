#pragma once
// `cnclab compare --group-by KEY`: runs grouped by a config key (or the
// repeats of one config), each metric as mean with its Student-t interval
// over the group's runs, and each later group against the first: the
// difference of means, Welch's t-test (two-sided p) and a percentile
// bootstrap interval of the difference (statistics.hpp). A difference whose
// p is not below alpha is marked not significant. No correction for several
// comparisons: with k groups, k - 1 tests at alpha each.
//
// One row per (metric, group) with the same columns in every format:
//   metric, group, n, mean, std, ci_low, ci_high,
//   diff, welch_t, df, p_value, boot_low, boot_high, significant
// (the difference columns are empty for the first group; intervals at
// level 1 - alpha).
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
  void validate() const;          // OptionError naming the field
};

struct RunGroup {
  std::string label;              // "trainer.type=sgdm", or the repeats' distinguishing keys
  std::vector<std::size_t> runs;  // indices into the runs, in input order
};

// Groups in order of first appearance. ConfigError when no run has the key
// (with "did you mean" over the runs' keys) or fewer than two groups result.
std::vector<RunGroup> group_runs(const std::vector<ComparedRun>& runs, const std::string& group_by);

struct GroupRow {
  std::string metric, group;
  SampleSummary summary;    // over the group's finite values of the metric
  bool reference = false;   // the first group: no difference columns
  WelchTest welch;          // group - first group
  Interval bootstrap;       // of group - first group
  std::string significant;  // "yes", "no", or "n/a" (test undefined); "" for the reference
};

// Every metric any run has, for every group.
std::vector<GroupRow> compare_groups(const std::vector<ComparedRun>& runs,
                                     const std::vector<RunGroup>& groups,
                                     const GroupCompareOptions& options);

void print_group_comparison(const std::vector<ComparedRun>& runs,
                            const GroupCompareOptions& options, CompareFormat format,
                            std::ostream& out);

// collect_runs (compare.hpp), then print_group_comparison. Returns 0.
int compare_groups_command(const std::vector<std::string>& inputs, const std::string& format,
                           const GroupCompareOptions& options, std::ostream& out);

}  // namespace cnclab
