#include "cnclab/studies/five_axis/ik_tables.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/data/ik_samples.hpp"
#include "cnclab/kinematics/joint_error.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/report/run_settings.hpp"
#include "cnclab/report/typed_table.hpp"
#include "cnclab/studies/five_axis/ik_runs.hpp"
#include "cnclab/train/sgdm.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

double metric(const RunRecord& r, const std::string& name) {
  const auto it = r.metrics.find(name);
  return it == r.metrics.end() ? NAN : it->second;
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
TableCell sgdm_setting(const IkAxisRun& r, double SgdmOptions::*field) {
  const auto* sgdm = trainer_options_if<SgdmOptions>(r.loaded.spec.trainer);
  return sgdm ? number_cell(sgdm->*field, table_number(sgdm->*field)) : missing_cell("-");
}

std::string integer(double v) {
  return std::to_string(static_cast<long long>(std::llround(v)));
}

// One value column of Table 5: an axis of a variant, or the paper's.
struct Column {
  std::size_t axis = 0;                // index into kIkAxes
  const IkVariant* variant = nullptr;  // nullptr: the paper's column
};

// Table 5's rows for `columns` (axes in groups: each variant, then the paper).
TypedTable table5(const std::vector<Column>& columns, const Reference& ref) {
  TypedTable t;
  t.columns = {label_column("", "group"), label_column("", "quantity")};
  for (const auto& c : columns) {
    const std::string header =
        std::string(kIkAxes[c.axis]) + " " + (c.variant ? c.variant->label : "paper");
    t.columns.push_back(number_column(header, machine_name(header)));  // "x_ours"
  }
  using Ours = std::function<TableCell(const IkAxisRun&)>;
  std::string group_key;  // csv/json carry the group on its continuation rows too
  const auto row = [&](const std::string& group, const std::string& label, const std::string& key,
                       const Ours& ours, bool integer_ref) {
    if (!group.empty()) group_key = machine_name(group);
    std::vector<TableCell> cells = {label_cell(group, group_key), label_cell(label, key)};
    for (const auto& c : columns) {
      if (!c.variant) {
        const double v = ref.rows.at(key)[c.axis];
        cells.push_back(number_cell(v, integer_ref ? integer(v) : table_number(v)));
      } else {
        const auto& run = c.variant->axes[c.axis];
        cells.push_back(run ? ours(*run) : missing_cell("n/a"));
      }
    }
    t.rows.push_back(cells);
  };
  const auto count = [](std::size_t n) {
    return number_cell(static_cast<double>(n), std::to_string(n));
  };
  row(
      "Dataset", "Training set", "training_set",
      [&](const IkAxisRun& r) { return count(r.record.split.train.size()); }, true);
  row(
      "", "Test set", "test_set",
      [&](const IkAxisRun& r) { return count(r.record.split.test.size()); }, true);
  row(
      "", "Validation set", "validation_set",
      [&](const IkAxisRun& r) { return count(r.record.split.validation.size()); }, true);
  row(
      "Number of neurons", "Input layer", "input_layer",
      [&](const IkAxisRun& r) { return count(r.record.model.inputs); }, true);
  row(
      "", "Hidden layer1", "hidden_layer1",
      [&](const IkAxisRun& r) {
        return r.record.model.hidden.size() > 0 ? count(r.record.model.hidden[0])
                                                : missing_cell("-");
      },
      true);
  row(
      "", "Hidden layer2", "hidden_layer2",
      [&](const IkAxisRun& r) {
        return r.record.model.hidden.size() > 1 ? count(r.record.model.hidden[1])
                                                : missing_cell("-");
      },
      true);
  row(
      "", "Output layer", "output_layer",
      [&](const IkAxisRun& r) { return count(r.record.model.outputs); }, true);
  row(
      "Learning rate", "LR", "learning_rate",
      [&](const IkAxisRun& r) { return sgdm_setting(r, &SgdmOptions::learning_rate); }, false);
  row(
      "Momentum parameter", "MU", "momentum",
      [&](const IkAxisRun& r) { return sgdm_setting(r, &SgdmOptions::momentum); }, false);
  row(
      "MSE-validation", "", "mse_validation",
      [&](const IkAxisRun& r) {
        const double v = metric(r.record, "validation.normalised_mse");
        return number_cell(v, table_number(v, 3));
      },
      false);
  row(
      "MSE-test", "", "mse_test",
      [&](const IkAxisRun& r) {
        const double v = metric(r.record, "test.normalised_mse");
        return number_cell(v, table_number(v, 3));
      },
      false);
  return t;
}

// The result files of every variant's networks, variant by variant.
std::vector<fs::path> result_files(const std::vector<IkVariant>& variants) {
  std::vector<fs::path> files;
  for (const auto& v : variants) {
    for (const auto& a : v.axes) {
      if (a && !a->selection.empty()) files.push_back(a->selection);
      if (a) files.push_back(a->result_file);
    }
  }
  return files;
}

// "<label> ran with profile quick (per the result files' configs): trainer:
// ...; model: hidden ..." of a variant's networks (report/run_settings.hpp).
std::string settings_note(const std::string& label, const std::string& profile,
                          const std::vector<const IkAxisRun*>& runs) {
  std::vector<std::string> configs;
  for (const IkAxisRun* r : runs) configs.push_back(r->record.resolved_yaml);
  return label + " " +
         ran_with(profile, configs,
                  {"trainer.type", "trainer.learning_rate", "trainer.momentum", "trainer.epochs",
                   "model.hidden"}) +
         ".";
}

void print_table5(const std::vector<IkVariant>& variants, const Reference& ref,
                  const fs::path& reference_file, const std::string& profile, TableFormat format,
                  std::ostream& out) {
  std::vector<const IkVariant*> shown;
  for (const auto& v : variants) {
    if (v.any()) shown.push_back(&v);
  }
  // Columns grouped by axis: our variants, then the paper (X, Y, Z only).
  std::vector<Column> columns;
  for (std::size_t a = 0; a < kIkAxes.size(); ++a) {
    for (const IkVariant* v : shown) columns.push_back({a, v});
    if (a < 3) columns.push_back({a, nullptr});
  }
  const std::string title =
      "Seed 004 Table 5: the obtained MLP parameters (ours beside the paper's; A and C: ours only)";
  // More than 12 value columns do not fit a terminal: X, Y, Z, then A, C.
  if (columns.size() <= 12) {
    print_table_title(out, format, title);
    table5(columns, ref).print(out, format);
  } else {
    const auto split =
        std::find_if(columns.begin(), columns.end(), [](const Column& c) { return c.axis >= 3; });
    print_table_title(out, format, title + ", X, Y, Z");
    table5({columns.begin(), split}, ref).print(out, format);
    print_table_title(out, format, title + ", A, C");
    table5({split, columns.end()}, ref).print(out, format);
  }

  TypedTable phys;
  phys.columns = {label_column("metric", "metric"),    label_column("variant", "variant"),
                  number_column("X [mm]", "x", "mm"),  number_column("Y [mm]", "y", "mm"),
                  number_column("Z [mm]", "z", "mm"),  number_column("A [deg]", "a", "deg"),
                  number_column("C [deg]", "c", "deg")};
  for (const char* name : {"rmse", "max_abs_error"}) {
    for (const IkVariant* v : shown) {
      std::vector<TableCell> cells = {
          label_cell(name == std::string("rmse") ? "RMSE" : "max |error|", name), v->label};
      for (std::size_t a = 0; a < kIkAxes.size(); ++a) {
        const double f = a >= 3 ? kDegPerRad : 1.0;
        if (!v->axes[a]) {
          cells.push_back(missing_cell("n/a"));
          continue;
        }
        const double e = f * metric(v->axes[a]->record, metric_name("test", name));
        cells.push_back(number_cell(e, table_number(e, 3)));
      }
      phys.rows.push_back(cells);
    }
  }
  print_table_title(out, format, "Test error in machine units");
  phys.print(out, format);

  const auto& s = variants.front().axes.front()->record;
  const std::string range =
      table_number(s.target_scaling.y_min) + ", " + table_number(s.target_scaling.y_max);
  const auto& text = ref.rows.at("text_split");
  std::vector<std::string> notes = {
      "Paper values: results/reference/ik_table5.yaml (" + ref.sources.at("mse_test") +
          "; split text: " + ref.sources.at("text_split") + ").",
      "Split: Table 5 prints " + integer(ref.rows.at("training_set")[0]) + " / " +
          integer(ref.rows.at("test_set")[0]) + " / " + integer(ref.rows.at("validation_set")[0]) +
          " (training / test / validation), which adds up to " +
          integer(ref.rows.at("training_set")[0] + ref.rows.at("test_set")[0] +
                  ref.rows.at("validation_set")[0]) +
          ", not the " + integer(text[2]) + " samples; we follow the text (" +
          ref.sources.at("text_split") + "): " + integer(text[0]) + " training, " +
          integer(text[1]) + " test, the rest validation.",
      "MSE in normalised units (metrics validation.normalised_mse, test.normalised_mse): targets "
      "min-max scaled to [" +
          range +
          "] on the training split (sigmoid outputs); the paper does not state its scaling, so "
          "its MSE values compare in magnitude only.",
      "Validation MSE is that of the returned weights (best epoch under early stopping).",
      "ours: the paper's sizes and SGDM settings (experiments/ik/); A and C networks are not in "
      "the paper, their sizes and settings are ours (ik_a.yaml, ik_c.yaml).",
      "search: the paper's heuristic search as a random search over both hidden sizes, learning "
      "rate and momentum, choosing on the validation split (the lowest validation.normalised_mse, "
      "as seed 004 Sec. 4.2: \"the best model corresponds to the lowest validation error\"); "
      "its MSE-test is reported after the choice, never used for it (experiments/ik_search/).",
      "trainbr: the ours networks trained with Levenberg-Marquardt + Bayesian regularisation "
      "(experiments/ik_trainbr/; no learning rate or momentum)."};
  for (const auto& v : variants) {
    std::vector<const IkAxisRun*> runs;
    for (const auto& a : v.axes) {
      if (a) runs.push_back(&*a);
    }
    if (!runs.empty()) notes.push_back(settings_note(v.label, profile, runs));
    for (const auto& note : v.notes) notes.push_back(v.label + ": " + note);
  }
  print_table_notes(out, format, notes);
  std::vector<fs::path> sources = {reference_file};
  for (const auto& f : result_files(variants)) sources.push_back(f);
  print_table_sources(out, format, sources);
}

// The variant's networks, with the sgdm network for an axis it lacks
// (listed in `borrowed`).
std::array<const IkAxisRun*, 5> networks(const IkVariant& v, const IkVariant& sgdm,
                                         std::string& borrowed) {
  std::array<const IkAxisRun*, 5> runs{};
  for (std::size_t a = 0; a < kIkAxes.size(); ++a) {
    runs[a] = v.axes[a] ? &*v.axes[a] : &*sgdm.axes[a];
    if (!v.axes[a]) borrowed += (borrowed.empty() ? "" : ", ") + std::string(kIkAxes[a]);
  }
  return runs;
}

void print_machine_error(const std::vector<IkVariant>& variants, const std::string& profile,
                         TableFormat format, std::ostream& out) {
  const IkVariant& sgdm = variants.front();
  const IkAxisRun& reference = *sgdm.axes.front();
  const RunRecord& first = reference.record;
  const auto* generator =
      dynamic_cast<const IkSamplesGenerator*>(reference.loaded.spec.dataset.generator.get());
  if (!generator) throw Error("tables ik: the IK experiments must use the ik_samples generator");
  const TttrrMachine machine(generator->options().machine);
  const auto n = static_cast<Eigen::Index>(first.split.test.size());

  TypedTable t;
  t.columns = {label_column("Networks", "networks"),
               label_column("Predicted joints", "predicted_joints"),
               number_column("tip mean [mm]", "tip_mean", "mm"),
               number_column("tip p95 [mm]", "tip_p95", "mm"),
               number_column("tip max [mm]", "tip_max", "mm"),
               number_column("axis mean [deg]", "axis_mean", "deg"),
               number_column("axis p95 [deg]", "axis_p95", "deg"),
               number_column("axis max [deg]", "axis_max", "deg")};
  std::vector<std::string> notes;
  std::vector<fs::path> sources;
  for (const auto& v : variants) {
    if (!v.any()) continue;
    std::string borrowed;
    const auto runs = networks(v, sgdm, borrowed);
    for (const IkAxisRun* r : runs) sources.push_back(r->result_file);
    notes.push_back(settings_note(v.label, profile, {runs.begin(), runs.end()}));
    Eigen::MatrixXd predicted(5, n), truth(5, n);
    for (std::size_t i = 0; i < 5; ++i) {
      const IkAxisRun& r = *runs[i];
      if (r.record.split.test != first.split.test || r.record.dataset_hash != first.dataset_hash) {
        throw Error("tables ik: " + r.source.string() + " and " + reference.source.string() +
                    " differ in dataset or test split; the machine-space error needs all five "
                    "networks on the same test samples (same seed, dataset and split)");
      }
      predicted.row(static_cast<Eigen::Index>(i)) = r.record.test_predictions.row(0);
      truth.row(static_cast<Eigen::Index>(i)) = r.record.test_targets.row(0);
    }
    const std::string label = v.label + (borrowed.empty() ? "" : " *");
    if (!borrowed.empty()) {
      notes.push_back(label + ": " + borrowed + " from ours (no " + v.label + " result)");
    }
    // csv/json carry the networks on every row and the predicted joints as
    // their letters ("x_y_z").
    const auto add = [&](const std::string& joints, const std::vector<int>& rows) {
      Eigen::MatrixXd mixed = truth;
      for (int row : rows) mixed.row(row) = predicted.row(row);
      const PoseErrors e = pose_errors(machine, mixed, truth);
      const ErrorSummary p = summarize_errors(e.position_mm);
      std::vector<double> axis_deg;
      for (double d : e.axis_rad) axis_deg.push_back(d * kDegPerRad);
      const ErrorSummary a = summarize_errors(axis_deg);
      std::string predicted_key;
      for (int row : rows) {
        if (!predicted_key.empty()) predicted_key += "_";
        predicted_key += machine_name(kIkAxes[static_cast<std::size_t>(row)]);
      }
      const auto num = [](double x) { return number_cell(x, table_number(x, 3)); };
      t.rows.push_back({label_cell(rows.size() == 5 ? label : "", label),
                        label_cell(joints, predicted_key), num(p.mean), num(p.p95), num(p.max),
                        num(a.mean), num(a.p95), num(a.max)});
    };
    add("X, Y, Z, A, C (all five)", {0, 1, 2, 3, 4});
    add("X, Y, Z (A, C exact)", {0, 1, 2});
    add("A, C (X, Y, Z exact)", {3, 4});
  }
  print_table_title(out, format,
                    "Machine-space error (beyond the paper): predicted joint sets through forward "
                    "kinematics, compared with the true pose, test split (n = " +
                        std::to_string(n) + ", machine offset d = " +
                        table_number(machine.options().offset_d) + " mm)");
  t.print(out, format);
  notes.insert(notes.begin(),
               {"tool tip: |P(predicted joints) - P(true joints)|; tool axis: angle between the "
                "two tool orientations; p95 = 95th percentile (linear interpolation).",
                "Rows with some joints exact show which networks the error comes from."});
  print_table_notes(out, format, notes);
  print_table_sources(out, format, sources);
}

// <variant>.<axis>.* of every network: the Table 5 rows (split sizes,
// normalised MSEs) and the machine-unit errors, from the same metric() calls.
void add_axis(Measurements& m, const std::string& prefix, std::size_t axis, const IkAxisRun& r) {
  m[prefix + ".training_set"] = static_cast<double>(r.record.split.train.size());
  m[prefix + ".test_set"] = static_cast<double>(r.record.split.test.size());
  m[prefix + ".validation_set"] = static_cast<double>(r.record.split.validation.size());
  m[prefix + ".mse_validation"] = metric(r.record, "validation.normalised_mse");
  m[prefix + ".mse_test"] = metric(r.record, "test.normalised_mse");
  // Machine units as the "Test error in machine units" table: mm, or degrees for A and C.
  const double f = axis >= 3 ? kDegPerRad : 1.0;
  m[prefix + ".rmse"] = f * metric(r.record, "test.rmse");
  m[prefix + ".max_abs_error"] = f * metric(r.record, "test.max_abs_error");
}

}  // namespace

void print_ik_tables(const TablesOptions& options, std::ostream& out) {
  const std::vector<IkVariant> variants = load_ik_variants(options);
  const fs::path reference_file = options.reference_file("ik_table5.yaml");
  const Reference ref = read_reference(reference_file);
  print_table5(variants, ref, reference_file, options.profile, options.format, out);
  print_machine_error(variants, options.profile, options.format, out);
}

Measurements measure_ik_tables(const TablesOptions& options) {
  Measurements m;
  for (const auto& v : load_ik_variants(options)) {
    for (std::size_t a = 0; a < kIkAxes.size(); ++a) {
      if (v.axes[a]) add_axis(m, v.key + "." + kIkAxes[a], a, *v.axes[a]);
    }
  }
  return m;
}

}  // namespace cnclab
