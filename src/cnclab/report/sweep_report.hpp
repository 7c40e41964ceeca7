#pragma once
// A sweep for people: the ranked table (mean ± std per point), the failed
// trials and the best trial (`cnclab sweep`, `cnclab sweep merge`).
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

namespace cnclab {

// The ranked table, failures and the best trial, for people. `name`: the
// sweep's own name (a `kind: sweep` file's), shown with the experiment it
// sweeps; "": the header names the experiment only. The table shows the
// metrics of the objective's split (validation by default; summary.h5 holds
// every split), each with its unit; below it the chosen point's test
// metrics, labelled as reported after the choice, and a warning when the
// objective is itself a test metric (objective_warning).
void print_summary(std::ostream& out, const SweepPlan& plan,
                   const std::vector<TrialOutcome>& outcomes, const SweepSummary& summary,
                   const std::filesystem::path& dir, const std::string& name = "");

// A sweep's summary.h5 as `sweep merge` prints it, read from the file alone
// (its trials as the summary recorded them; the "best trial" path beside
// the summary, as merge's), and a note when the file records another best
// trial (chosen by an older rule). `cnclab show SUMMARY.h5`.
void print_stored_summary(const std::filesystem::path& file, std::ostream& out);

}  // namespace cnclab
