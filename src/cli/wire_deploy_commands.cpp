// CLI11 wiring of predict and export (cli_wiring.hpp); the work is in
// cnclab/deploy/.
#include <iostream>
#include <memory>

#include "cli/cli_wiring.hpp"
#include "cnclab/deploy/model_export.hpp"
#include "cnclab/deploy/predict_command.hpp"

namespace cnclab {
namespace {

struct PredictArgs {
  PredictRequest request;
  std::string initial;
  bool quiet = false;
};

void add_predict(CLI::App& app, CommandAction& action) {
  auto a = std::make_shared<PredictArgs>();
  auto* predict = app.add_subcommand(
      "predict", "Apply a trained network to a dataset, a dataset config or a CSV of raw inputs");
  predict->add_option("result", a->request.result, "Result file of a training run (RESULT.h5)")
      ->required()
      ->check(CLI::ExistingFile);
  predict
      ->add_option("input", a->request.input,
                   "A dataset (.h5), a dataset config (.yaml, generated into the dataset cache: "
                   "a new surface, face or path) or a CSV of raw inputs (.csv, a header naming "
                   "the network's input columns, optionally 'name [unit]')")
      ->required();
  predict->add_option("overrides", a->request.overrides, "Overrides key=value of a dataset config");
  predict
      ->add_option("-o,--output", a->request.out, "Output file, .h5 or .csv (written atomically)")
      ->required();
  predict
      ->add_option("--split", a->request.options.split,
                   "all, or the result's own train, validation or test part (INPUT must be its "
                   "training dataset)")
      ->capture_default_str();
  predict->add_option("--initial", a->initial,
                      "narx: start the closed loop from the first measured samples (measured, the "
                      "default with measured targets) or from standstill (rest)");
  predict->add_option("--data-dir", a->request.data.data_dir, "Dataset cache folder")
      ->capture_default_str();
  add_quiet_flag(*predict, a->quiet);
  predict->footer(
      "Columns out: sample; mlp: <target>.predicted (and .measured); narx: <target>.closed_loop, "
      ".open_loop (with measured targets), .measured, in the dataset's and the physical units, "
      "and a study's per-tick columns (seed 002: contour_error.*). OUT records the result's "
      "identity and the input's hash.\n"
      "Examples:\n"
      "  cnclab predict results/step_error_surface1/step_error_surface1-5a3c0f1e.h5 "
      "configs/datasets/step_error_surface3.yaml -o surface3.csv\n"
      "  cnclab predict RESULT.h5 DATASET.h5 --split test -o test.h5\n"
      "  cnclab predict NARX_RESULT.h5 path.yaml dataset.seed=7 -o path.h5   # planning, "
      "simulated drives, predicted contour error per tick");
  predict->callback([a, &action] {
    action = [a] {
      if (!a->initial.empty()) a->request.options.initial = parse_initial_state(a->initial);
      a->request.data.log = a->quiet ? nullptr : &std::cerr;
      for (const auto& line : run_predict(a->request)) std::cout << line << "\n";
      return 0;
    };
  });
}

struct ExportArgs {
  std::filesystem::path result;
  ExportOptions options;
  bool quiet = false;
};

void add_export(CLI::App& app, CommandAction& action) {
  auto a = std::make_shared<ExportArgs>();
  auto* exp = app.add_subcommand(
      "export", "Write a trained network as C99 for a controller, or as a PyTorch module");
  exp->add_option("result", a->result, "Result file of a training run (RESULT.h5)")
      ->required()
      ->check(CLI::ExistingFile);
  exp->add_option("--format", a->options.format,
                  "c: NAME.h and NAME.c (C99, static const hex-float weights, no malloc, only "
                  "<math.h>); torch: NAME.py, a torch.nn.Module")
      ->capture_default_str();
  exp->add_option("-o,--out-dir", a->options.out_dir, "Folder to write into (created)")->required();
  exp->add_option("--name", a->options.name,
                  "NAME of the files and functions (default: the experiment's name)");
  exp->add_option("--precision", a->options.precision,
                  "c: double, or float (the header states the bound on the difference)")
      ->capture_default_str();
  exp->add_option("--data-dir", a->options.data.data_dir,
                  "Dataset cache folder (narx ranges, the float bound's data)")
      ->capture_default_str();
  add_quiet_flag(*exp, a->quiet);
  exp->footer(
      "API: mlp  int NAME_predict(const NAME_real in[], NAME_real out[]);\n"
      "     narx void NAME_init(NAME_state *s);  int NAME_step(NAME_state *s, const NAME_real "
      "in[], NAME_real out[]);\n"
      "Examples:\n"
      "  cnclab export results/contour_error_narx/RESULT.h5 --format c -o controller/\n"
      "  cnclab export RESULT.h5 --format c --precision float --name ik_x -o m4/\n"
      "  cnclab export RESULT.h5 --format torch -o python/");
  exp->callback([a, &action] {
    action = [a] {
      a->options.data.log = a->quiet ? nullptr : &std::cerr;
      for (const auto& line : export_model(a->result, a->options).lines) std::cout << line << "\n";
      return 0;
    };
  });
}

}  // namespace

void add_deploy_commands(CLI::App& app, CommandAction& action) {
  add_predict(app, action);
  add_export(app, action);
}

}  // namespace cnclab
