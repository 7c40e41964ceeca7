#pragma once
// The seed-to-seed spread of the step-error study's headline rows: the `kind: sweep` files the
// manifest's `repeats:` names (experiments/step_error/tuned/seeds_*.yaml), each one swept key with
// `repeats` seeds per value, read as `cnclab tables step-error` needs them:
// per point (value of the key) the figures of every complete trial
// (run_figures, step_error_measures.hpp), so a table row gives their mean ±
// std and a note Welch's test between two points (step_error_seed_notes.hpp).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cnclab/report/tables.hpp"
#include "cnclab/studies/step_error/step_error_manifest.hpp"

namespace cnclab {

// The keep probability of no dropout: Table 2's sweep point beside its p.
inline constexpr double kNoDropout = 1.0;

// One value of the swept key over its seeds.
struct RepeatedPoint {
  // The value as the plan writes it ("0.5"); of an init_from mapping, its
  // normaliser ("refit", "keep").
  std::string value;
  // run_figures of each complete trial, in repeat order, and its seed.
  std::vector<std::map<std::string, double>> runs;
  std::vector<std::uint64_t> seeds;
  std::size_t planned = 0;  // trials planned at this value (complete or not)

  double number() const;  // value as a number; NaN when it is not one
  // `figure` over the complete trials, NaN values left out.
  std::vector<double> sample(const std::string& figure) const;
};

struct RepeatedSweep {
  std::filesystem::path file;                                 // the kind: sweep file
  std::filesystem::path dir;                                  // results/<name>/sweep-<plan hash>
  std::string key;                                            // the swept key
  std::vector<RepeatedPoint> points;                          // plan order
  std::vector<std::filesystem::path> sources;                 // the result files read
  std::vector<std::string> configs;                           // their resolved configs
  const RepeatedPoint* find(const std::string& value) const;  // nullptr when absent
  const RepeatedPoint* find(double number) const;
};

struct StepErrorRepeats {
  std::string variant;  // the variant whose headline rows these repeat
  // model.dropout.keep_probability: Table 2's p and 1.0, with a validation
  // split (chosen on validation, reported on test).
  RepeatedSweep table2;
  RepeatedSweep surface1;                      // surface 1 itself (keep 1.0, 70/30)
  RepeatedSweep surface2_ft15, surface3_ft15;  // init_from: refit and keep chains
};

// Table 2 over seeds: the point of Table 2's sweep (a keep probability, not
// 1.0: no dropout) with the lowest mean `figure` over at least 2 seeds;
// nullptr when none has 2. The choice is on "validation_mse"
// (step_error_measures.hpp); on "test_mse" it is the paper's reading, shown
// beside it.
const RepeatedPoint* table2_choice_over_seeds(const RepeatedSweep& table2,
                                              const std::string& figure);

// The complete trials of one sweep file with one swept key under the
// tables' results folder and profile. MissingResults naming the command
// that makes them while any trial has not run; ConfigError when the file
// sweeps other than one key.
RepeatedSweep load_repeated_sweep(const std::filesystem::path& file, const TablesOptions& options);
StepErrorRepeats load_step_error_repeats(const StudyRepeats& repeats, const TablesOptions& options);

}  // namespace cnclab
