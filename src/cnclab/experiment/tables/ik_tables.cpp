#include "cnclab/experiment/tables/ik_tables.hpp"

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/data/ik_samples.hpp"
#include "cnclab/experiment/metrics.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/runner.hpp"
#include "cnclab/experiment/text_table.hpp"
#include "cnclab/kinematics/joint_error.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr std::array<const char*, 5> kAxes = {"X", "Y", "Z", "A", "C"};

struct AxisRun {
  std::string axis;
  fs::path experiment;
  LoadedExperiment loaded;
  RunRecord record;
};

AxisRun load_axis(const TablesOptions& o, const std::string& axis) {
  std::string lower = axis;
  lower[0] = static_cast<char>(lower[0] - 'A' + 'a');
  AxisRun run;
  run.axis = axis;
  run.experiment = o.experiments_dir / "ik" / ("ik_" + lower + ".yaml");
  if (!fs::exists(run.experiment)) {
    throw MissingResults(run.experiment.string() + ": experiment file not found");
  }
  run.loaded = load_experiment(run.experiment, std::vector<std::string>{}, std::nullopt, o.profile);
  const fs::path result = result_path(run.loaded, o.results_dir);
  if (!fs::exists(result)) {
    throw MissingResults("no result for " + run.experiment.string() + " (expected " +
                         result.string() + "); run `cnclab reproduce " +
                         (o.experiments_dir / "ik").string() + "` first");
  }
  run.record = read_result(result);
  if (run.record.target_names != std::vector<std::string>{axis}) {
    throw Error(result.string() + ": expected the single target " + axis);
  }
  if (run.record.provenance.status != "complete") {
    throw Error(result.string() + ": training failed (" + run.record.provenance.failure_reason +
                ")");
  }
  return run;
}

// Validation MSE of the returned weights (normalised units): the best epoch
// when early stopping restored it, else the last epoch.
double validation_mse(const RunRecord& r) {
  const auto& h = r.training.history;
  if (h.empty()) return NAN;
  if (r.training.termination == Termination::early_stop && r.training.best_epoch >= 1) {
    return h[r.training.best_epoch - 1].validation_loss;
  }
  return h.back().validation_loss;
}

struct Reference {
  std::map<std::string, std::vector<double>> rows;
  std::map<std::string, std::string> sources;
};

Reference read_reference(const fs::path& file) {
  if (!fs::exists(file)) throw MissingResults(file.string() + ": reference file not found");
  const ConfigDocument doc = ConfigDocument::load(file);
  const ConfigReader root = doc.root();
  const auto axes = root.require<std::vector<std::string>>("axes");
  if (axes != std::vector<std::string>{"X", "Y", "Z"}) root.fail("axes", "must be [X, Y, Z]");
  Reference ref;
  const ConfigReader rows = root.section("rows");
  for (const char* key : {"training_set", "test_set", "validation_set", "input_layer",
                          "hidden_layer1", "hidden_layer2", "output_layer", "learning_rate",
                          "momentum", "mse_validation", "mse_test"}) {
    const ConfigReader row = rows.section(key);
    ref.sources[key] = row.require<std::string>("source");
    ref.rows[key] = row.require<std::vector<double>>("values");
    if (ref.rows[key].size() != 3) row.fail("values", "must have 3 values (X, Y, Z)");
  }
  const ConfigReader text = root.section("text_split");
  ref.sources["text_split"] = text.require<std::string>("source");
  ref.rows["text_split"] = {static_cast<double>(text.require<std::size_t>("training")),
                            static_cast<double>(text.require<std::size_t>("test")),
                            static_cast<double>(text.require<std::size_t>("total"))};
  doc.check_all_consumed();
  return ref;
}

// An SGDM setting of the run's trainer; "-" for other trainers (lm, trainbr).
std::string sgdm_setting(const AxisRun& r, double SgdmOptions::*field) {
  const auto* sgdm = std::get_if<SgdmOptions>(&r.loaded.spec.trainer);
  return sgdm ? table_number(sgdm->*field) : "-";
}

std::string integer(double v) {
  return std::to_string(static_cast<long long>(std::llround(v)));
}

void print_table5(const std::vector<AxisRun>& runs, const Reference& ref, TableFormat format,
                  std::ostream& out) {
  TextTable t;
  t.header = {"", ""};
  for (const auto& run : runs) {
    t.header.push_back(run.axis + " ours");
    if (run.axis != "A" && run.axis != "C") t.header.push_back(run.axis + " paper");
  }
  using Ours = std::function<std::string(const AxisRun&)>;
  const auto row = [&](const std::string& group, const std::string& label, const std::string& key,
                       const Ours& ours, bool integer_ref) {
    std::vector<std::string> cells = {group, label};
    for (std::size_t i = 0; i < runs.size(); ++i) {
      cells.push_back(ours(runs[i]));
      if (i < 3) {
        const double v = ref.rows.at(key)[i];
        cells.push_back(integer_ref ? integer(v) : table_number(v));
      }
    }
    t.rows.push_back(cells);
  };
  const auto count = [](std::size_t n) { return std::to_string(n); };
  row(
      "Dataset", "Training set", "training_set",
      [&](const AxisRun& r) { return count(r.record.split.train.size()); }, true);
  row(
      "", "Test set", "test_set",
      [&](const AxisRun& r) { return count(r.record.split.test.size()); }, true);
  row(
      "", "Validation set", "validation_set",
      [&](const AxisRun& r) { return count(r.record.split.validation.size()); }, true);
  row(
      "Number of neurons", "Input layer", "input_layer",
      [&](const AxisRun& r) { return count(r.record.model.inputs); }, true);
  row(
      "", "Hidden layer1", "hidden_layer1",
      [&](const AxisRun& r) {
        return r.record.model.hidden.size() > 0 ? count(r.record.model.hidden[0]) : "-";
      },
      true);
  row(
      "", "Hidden layer2", "hidden_layer2",
      [&](const AxisRun& r) {
        return r.record.model.hidden.size() > 1 ? count(r.record.model.hidden[1]) : "-";
      },
      true);
  row(
      "", "Output layer", "output_layer",
      [&](const AxisRun& r) { return count(r.record.model.outputs); }, true);
  row(
      "Learning rate", "LR", "learning_rate",
      [&](const AxisRun& r) { return sgdm_setting(r, &SgdmOptions::learning_rate); }, false);
  row(
      "Momentum parameter", "MU", "momentum",
      [&](const AxisRun& r) { return sgdm_setting(r, &SgdmOptions::momentum); }, false);
  row(
      "MSE-validation", "", "mse_validation",
      [&](const AxisRun& r) { return table_number(validation_mse(r.record), 3); }, false);
  row(
      "MSE-test", "", "mse_test",
      [&](const AxisRun& r) { return table_number(normalised_test_mse(r.record), 3); }, false);

  print_table_title(out, format,
                    "Seed 004 Table 5: the obtained MLP parameters (ours beside the paper's; A and "
                    "C: ours only)");
  t.print(out, format);

  TextTable phys;
  phys.header = {"Test error in machine units", "X [mm]", "Y [mm]", "Z [mm]", "A [deg]", "C [deg]"};
  std::vector<std::string> rmse = {"RMSE"}, maxe = {"max |error|"};
  for (const auto& r : runs) {
    const double f = (r.axis == "A" || r.axis == "C") ? kDegPerRad : 1.0;
    rmse.push_back(table_number(f * r.record.metrics.at("rmse"), 3));
    maxe.push_back(table_number(f * r.record.metrics.at("max_abs_error"), 3));
  }
  phys.rows = {rmse, maxe};
  print_table_title(out, format, "Test error in machine units");
  phys.print(out, format);

  const auto& s = runs.front().record;
  const std::string range =
      table_number(s.target_scaling.y_min) + ", " + table_number(s.target_scaling.y_max);
  const auto& text = ref.rows.at("text_split");
  print_table_notes(
      out, format,
      {"Paper values: results/reference/ik_table5.yaml (" + ref.sources.at("mse_test") +
           "; split text: " + ref.sources.at("text_split") + ").",
       "Split: Table 5 prints " + integer(ref.rows.at("training_set")[0]) + " / " +
           integer(ref.rows.at("test_set")[0]) + " / " + integer(ref.rows.at("validation_set")[0]) +
           " (training / test / validation), which adds up to " +
           integer(ref.rows.at("training_set")[0] + ref.rows.at("test_set")[0] +
                   ref.rows.at("validation_set")[0]) +
           ", not the " + integer(text[2]) + " samples; we follow the text (" +
           ref.sources.at("text_split") + "): " + integer(text[0]) + " training, " +
           integer(text[1]) + " test, the rest validation.",
       "MSE in normalised units: targets min-max scaled to [" + range +
           "] on the training split (sigmoid outputs); the paper does not state its scaling, so "
           "its MSE values compare in magnitude only.",
       "Validation MSE is that of the returned weights (best epoch under early stopping).",
       "A and C networks are not in the paper; their sizes and settings are ours "
       "(experiments/ik/ik_a.yaml, ik_c.yaml)."});
}

void print_machine_error(const std::vector<AxisRun>& runs, TableFormat format, std::ostream& out) {
  const RunRecord& first = runs.front().record;
  for (const auto& r : runs) {
    if (r.record.split.test != first.split.test || r.record.dataset_hash != first.dataset_hash) {
      throw Error("tables ik: " + r.experiment.string() + " and " +
                  runs.front().experiment.string() +
                  " differ in dataset or test split; the machine-space error needs all five "
                  "networks on the same test samples (same seed, dataset and split)");
    }
  }
  const auto* generator =
      dynamic_cast<const IkSamplesGenerator*>(runs.front().loaded.spec.dataset.generator.get());
  if (!generator) throw Error("tables ik: the IK experiments must use the ik_samples generator");
  const TttrrMachine machine(generator->options().machine);

  const auto n = static_cast<Eigen::Index>(first.split.test.size());
  Eigen::MatrixXd predicted(5, n), truth(5, n);
  for (std::size_t i = 0; i < 5; ++i) {
    predicted.row(static_cast<Eigen::Index>(i)) = runs[i].record.test_predictions.row(0);
    truth.row(static_cast<Eigen::Index>(i)) = runs[i].record.test_targets.row(0);
  }
  TextTable t;
  t.header = {"Predicted joints", "tip mean [mm]",  "tip p95 [mm]",  "tip max [mm]",
              "axis mean [deg]",  "axis p95 [deg]", "axis max [deg]"};
  const auto add = [&](const std::string& label, const std::vector<int>& rows) {
    Eigen::MatrixXd mixed = truth;
    for (int row : rows) mixed.row(row) = predicted.row(row);
    const PoseErrors e = pose_errors(machine, mixed, truth);
    const ErrorSummary p = summarize_errors(e.position_mm);
    std::vector<double> axis_deg;
    for (double v : e.axis_rad) axis_deg.push_back(v * kDegPerRad);
    const ErrorSummary a = summarize_errors(axis_deg);
    t.rows.push_back({label, table_number(p.mean, 3), table_number(p.p95, 3),
                      table_number(p.max, 3), table_number(a.mean, 3), table_number(a.p95, 3),
                      table_number(a.max, 3)});
  };
  add("X, Y, Z, A, C (all five networks)", {0, 1, 2, 3, 4});
  add("X, Y, Z (A, C exact)", {0, 1, 2});
  add("A, C (X, Y, Z exact)", {3, 4});
  print_table_title(out, format,
                    "Machine-space error (beyond the paper): predicted joint sets through forward "
                    "kinematics, compared with the true pose, test split (n = " +
                        std::to_string(n) + ", machine offset d = " +
                        table_number(machine.options().offset_d) + " mm)");
  t.print(out, format);
  print_table_notes(
      out, format,
      {"tool tip: |P(predicted joints) - P(true joints)|; tool axis: angle between the two tool "
       "orientations; p95 = 95th percentile (linear interpolation).",
       "Rows with some joints exact show which networks the error comes from."});
}

}  // namespace

void print_ik_tables(const TablesOptions& options, std::ostream& out) {
  std::vector<AxisRun> runs;
  for (const char* axis : kAxes) runs.push_back(load_axis(options, axis));
  const Reference ref = read_reference(options.reference_dir / "ik_table5.yaml");
  print_table5(runs, ref, options.format, out);
  print_machine_error(runs, options.format, out);
}

}  // namespace cnclab
