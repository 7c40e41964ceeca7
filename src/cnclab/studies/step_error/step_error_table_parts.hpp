#pragma once
// What the step-error tables share about the manifest's variants: their row
// labels, the footer of the result files read, and the notes that say what
// each variant's runs actually ran with, read from the result files'
// resolved configs (report/run_settings.hpp), never from the manifest's
// description: a profile that swaps a variant's training shows under the
// table.
#include <filesystem>
#include <functional>
#include <map>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "cnclab/report/typed_table.hpp"
#include "cnclab/studies/step_error/step_error_study.hpp"

namespace cnclab {

// `v` with `decimals` decimals (core/format.hpp's fixed_decimals), or "-"
// for NaN (a cell without a value).
std::string fixed_or_dash(double v, int decimals);

// "ours, tuned"
std::string ours(const StudyVariant& v);
// A source ("ours, tuned") as a label, carried as "ours_tuned" by csv/json.
TableCell source_cell(const std::string& label);

// A table's footer: the paper's numbers file (`reference`, unless empty),
// then the result files of `runs`.
void print_sources(std::ostream& out, TableFormat format, const std::filesystem::path& reference,
                   const std::vector<const StepErrorRun*>& runs);

// The runs of the experiment files `files` (a Table 2 or fine-tuning map).
std::vector<const StepErrorRun*> study_runs(const StepErrorStudy& s,
                                            const std::map<double, std::filesystem::path>& files);

// The settings a step-error table's notes name (report/run_settings.hpp):
// the trainer's, the initialisation's and the dropout's.
std::vector<std::string> step_error_settings_keys();

// One note per variant, its runs in this table given by `runs_of`: "Variant
// paper (<manifest note>) ran with profile quick (per the result files'
// configs): trainer: type sgdm, ...; model: ..."; a variant that ran the same
// training as one before it says so. A variant with no run in the table
// gets no note.
std::vector<std::string> variant_settings_notes(
    const StepErrorStudy& s,
    const std::function<std::vector<const StepErrorRun*>(const StudyVariant&)>& runs_of);

}  // namespace cnclab
