#pragma once
// Small trainings of every model kind through `cnclab run` (the papers'
// architectures on a few samples and epochs: the code paths of the full
// studies in seconds), and the C compilers the exports are checked with.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "common/process.hpp"

namespace cnclab::testing {

inline const std::string kCnclab = CNCLAB_BINARY_DIR "/cnclab";

// `cnclab ARGS` in `dir` (results in dir/results, datasets in dir/data).
inline ShellResult cnclab(const std::filesystem::path& dir, const std::string& args) {
  return run_shell(dir, kCnclab + " " + args);
}

// Seed 000's 73-28-20-1 ReLU network with dropout on 144 samples of surface 1
// (its quick profile's trainer: the paper's N(0, 1) weights diverge in a few
// mini-batch epochs).
inline const std::string kStepErrorMlp = CNCLAB_SOURCE_DIR
    "/experiments/step_error/surface1.yaml --profile quick "
    "dataset.options.lines=12 dataset.options.points_per_line=12 "
    "trainer.epochs=3";
// Seed 004's 5-25-11-1 sigmoid network of the X axis, minmax scaling, 243 poses.
inline const std::string kIkMlp = CNCLAB_SOURCE_DIR
    "/experiments/ik/ik_x.yaml dataset.options.values_per_input=3 "
    "split.train_count=120 split.test_count=60 trainer.epochs=30";
// Seed 002's NARX (12 tanh units, 4 + 4 delays) on a short path, 1200 samples.
inline const std::string kNarx = CNCLAB_SOURCE_DIR
    "/experiments/contour_error/narx.yaml "
    "dataset.options.path.control_points=12 dataset.options.runs=2 "
    "dataset.options.samples=1200 "
    "'trainer.stages=[{mode: open_loop, type: trainbr, epochs: 4}, "
    "{mode: closed_loop, type: trainbr, epochs: 1}]'";

// Trains `experiment_args` in `dir`; the result file (relative to dir).
inline std::string train(const std::filesystem::path& dir, const std::string& experiment_args) {
  const ShellResult r =
      cnclab(dir, "run " + experiment_args + " --quiet --out results --data-dir data");
  EXPECT_EQ(r.code, 0) << r.err << r.out;
  return r.out.substr(0, r.out.find('\n'));
}

// True when `command` runs (a compiler, python3 with torch); else the test
// is skipped saying what is missing.
inline bool have(const std::string& command) {
  return std::system((command + " >/dev/null 2>&1").c_str()) == 0;
}

inline std::vector<std::vector<double>> read_numbers(const std::filesystem::path& file) {
  std::vector<std::vector<double>> rows;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    std::istringstream s(line);
    std::vector<double> row;
    for (std::string cell; s >> cell;) row.push_back(std::strtod(cell.c_str(), nullptr));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace cnclab::testing
