#include "cnclab/studies/step_error/step_error_study.hpp"

#include <algorithm>
#include <cmath>

#include "cnclab/experiment/result_inference.hpp"

namespace cnclab {
namespace fs = std::filesystem;

StepErrorRun step_error_run(RunRecord record, const fs::path& file) {
  StepErrorRun run;
  run.name = record.experiment;
  run.file = file;
  run.record = std::move(record);
  if (run.record.provenance.status != "complete") {
    // Table 2 shows a diverged keep probability as such; elsewhere it is an
    // error (load_step_error_study).
    run.failure =
        run.file.string() + ": training failed (" + run.record.provenance.failure_reason + ")";
    return run;
  }
  if (run.record.target_units != std::vector<std::string>{"µm"}) {
    throw Error(run.file.string() + ": expected one step-error target in µm");
  }
  const auto& p = run.record.test_predictions;
  const auto& t = run.record.test_targets;
  run.figures = error_figures(std::vector<double>(p.data(), p.data() + p.size()),
                              std::vector<double>(t.data(), t.data() + t.size()));
  return run;
}

double inference_test_mse(const StepErrorRun& run, DropoutInference inference) {
  if (!run.failure.empty()) return NAN;
  const Eigen::MatrixXd* predictions = test_predictions_by(run.record, inference);
  return predictions ? normalised_test_mse(run.record, *predictions) : NAN;
}

double inference_validation_mse(const StepErrorRun& run, DropoutInference inference) {
  if (!run.failure.empty()) return NAN;
  const std::map<std::string, double>* metrics = metrics_by(run.record, inference);
  if (!metrics) return NAN;
  const auto it = metrics->find("validation.normalised_mse");
  return it == metrics->end() ? NAN : it->second;
}

std::vector<fs::path> step_error_experiment_files(const TablesOptions& o) {
  const StudyManifest m = read_step_error_manifest(o.config_file("studies/step_error_tables.yaml"));
  std::vector<fs::path> files;
  for (const auto& v : m.variants) {
    for (const auto* numbered : {&v.table2, &v.surface2, &v.surface3}) {
      for (const auto& [key, f] : *numbered) files.push_back(f);
    }
    files.push_back(v.surface1);
    files.push_back(v.surface1_no_dropout);
  }
  for (const auto& n : m.normaliser) {
    files.push_back(n.surface2);
    files.push_back(n.surface3);
  }
  if (m.repeats) {
    files.insert(files.end(), {m.repeats->table2, m.repeats->surface1, m.repeats->surface2_ft15,
                               m.repeats->surface3_ft15});
    if (!m.repeats->search.empty()) files.push_back(m.repeats->search);
  }
  files.push_back(o.experiment_file("step_error/table8_timing.yaml"));
  return files;
}

StepErrorStudy load_step_error_study(const TablesOptions& o) {
  StepErrorStudy s;
  s.profile = o.profile;
  s.manifest = read_step_error_manifest(o.config_file("studies/step_error_tables.yaml"));
  s.reference_file = o.reference_file("seed000_step_error.yaml");
  s.ref = read_seed000_reference(s.reference_file);
  std::vector<fs::path> files;
  for (const auto& v : s.manifest.variants) {
    for (const auto& [p, f] : v.table2) files.push_back(f);
    files.push_back(v.surface1);
    files.push_back(v.surface1_no_dropout);
    for (const auto& [pct, f] : v.surface2) files.push_back(f);
    for (const auto& [pct, f] : v.surface3) files.push_back(f);
  }
  for (const auto& n : s.manifest.normaliser) {
    files.push_back(n.surface2);
    files.push_back(n.surface3);
  }
  std::vector<fs::path> unique;
  for (const auto& f : files) {
    if (std::find(unique.begin(), unique.end(), f) == unique.end()) unique.push_back(f);
  }
  std::vector<StoredResult> stored = table_store(o).get_all(unique, Accept::complete_or_failed);
  for (std::size_t i = 0; i < unique.size(); ++i) {
    s.runs.emplace(unique[i], step_error_run(std::move(stored[i].record), stored[i].file));
  }
  for (const auto& v : s.manifest.variants) {
    for (const auto& [p, f] : v.table2) files.erase(std::find(files.begin(), files.end(), f));
  }
  for (const auto& f : files) {
    if (!s.runs.at(f).failure.empty()) throw Error(s.runs.at(f).failure);
  }
  if (s.manifest.repeats) s.repeats = load_step_error_repeats(*s.manifest.repeats, o);
  if (s.manifest.repeats && !s.manifest.repeats->search.empty()) {
    s.search = Table2Search{load_searched_space(s.manifest.repeats->table2, o),
                            load_searched_space(s.manifest.repeats->search, o)};
  }
  return s;
}

}  // namespace cnclab
