#include "cnclab/studies/step_error/step_error_table_parts.hpp"

#include <cmath>

#include "cnclab/core/format.hpp"
#include "cnclab/report/run_settings.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// The settings the notes name: the training, then the network's dropout
// (what the paper's variant and its profiles change).
const std::vector<std::string> kTrainingKeys = {"trainer.type",          "trainer.batch_size",
                                                "trainer.learning_rate", "trainer.momentum",
                                                "trainer.epochs",        "model.init.weights.type"};
const std::vector<std::string> kDropoutKeys = {"model.dropout.keep_probability",
                                               "model.dropout.inference"};

}  // namespace

std::string fixed_or_dash(double v, int decimals) {
  return std::isnan(v) ? "-" : fixed_decimals(v, decimals);
}

std::string ours(const StudyVariant& v) {
  return "ours, " + v.name;
}

TableCell source_cell(const std::string& label) {
  return label_cell(label, machine_name(label));
}

void print_sources(std::ostream& out, TableFormat format, const fs::path& reference,
                   const std::vector<const StepErrorRun*>& runs) {
  std::vector<fs::path> files;
  if (!reference.empty()) files.push_back(reference);
  for (const StepErrorRun* r : runs) files.push_back(r->file);
  print_table_sources(out, format, files);
}

std::vector<const StepErrorRun*> study_runs(const StepErrorStudy& s,
                                            const std::map<double, fs::path>& files) {
  std::vector<const StepErrorRun*> runs;
  for (const auto& [key, file] : files) runs.push_back(&s.at(file));
  return runs;
}

std::vector<std::string> step_error_settings_keys() {
  std::vector<std::string> keys = kTrainingKeys;
  keys.insert(keys.end(), kDropoutKeys.begin(), kDropoutKeys.end());
  return keys;
}

std::vector<std::string> variant_settings_notes(
    const StepErrorStudy& s,
    const std::function<std::vector<const StepErrorRun*>(const StudyVariant&)>& runs_of) {
  const std::vector<std::string> keys = step_error_settings_keys();
  std::vector<std::string> notes;
  std::vector<std::pair<std::string, std::string>> trainings;  // variant, training text
  for (const auto& v : s.manifest.variants) {
    std::vector<std::string> configs;
    for (const StepErrorRun* r : runs_of(v)) configs.push_back(r->record.resolved_yaml);
    if (configs.empty()) continue;  // no run of this variant in the table
    std::string note = "Variant " + v.name + (v.note.empty() ? "" : " (" + v.note + ")") + " " +
                       ran_with(s.profile, configs, keys);
    const std::string training = run_settings(configs, kTrainingKeys);
    for (const auto& [earlier, text] : trainings) {
      if (text == training) {
        note += "; the same training as variant " + earlier + "'s";
        break;
      }
    }
    trainings.emplace_back(v.name, training);
    notes.push_back(note + ".");
  }
  return notes;
}

}  // namespace cnclab
