#pragma once
// Random train / validation / test splits of sample indices.
#include <cstddef>
#include <optional>
#include <vector>

#include "cnclab/core/fields.hpp"
#include "cnclab/core/rng.hpp"

namespace cnclab {

// random: the partition of make_random_split. sequential_halves: the samples
// in time order, the first half (N / 2, rounded down) for training, the rest
// for validation, no test part (seed 002: "the first half for training, the
// second for validation"; a time series for a recurrent model must not be
// shuffled). The fractions and counts apply to random only.
enum class SplitMode { random, sequential_halves };

struct SplitOptions {
  double train_fraction = 0.7;       // share of all samples used for training (seed 000: 70 %)
  double validation_fraction = 0.0;  // share held out of training for early stopping
  // test = the rest. validate(): train in [0, 1], validation in [0, 1), sum <= 1.
  // An empty training part (train 0) is a valid split: an evaluation-only
  // experiment (trainer.epochs 0, seed 000's 0 % fine-tuning) tests on all
  // samples; whether a run can train on the part is the experiment's check.
  //
  // Counts instead of fractions (seed 004 Sec. 4.2: 1042 training, 1040 test,
  // the rest validation). Setting train_count selects counts and the
  // fractions are unused. Of validation_count and test_count at most one may
  // be absent and takes the rest (both absent: no validation, test = rest);
  // when all three are given they must add up to the sample count.
  std::optional<std::size_t> train_count = std::nullopt;
  std::optional<std::size_t> validation_count = std::nullopt;
  std::optional<std::size_t> test_count = std::nullopt;
  SplitMode mode = SplitMode::random;  // last: SplitOptions{0.7, 0.1} stays valid

  bool uses_counts() const { return train_count.has_value(); }
  void validate() const;
  // validate() and, with counts, that they fit n samples (OptionError naming
  // the count).
  void validate_for(std::size_t n) const;
  // The part sizes for n samples: {train, validation, test}.
  struct Sizes {
    std::size_t train = 0, validation = 0, test = 0;
  };
  Sizes sizes(std::size_t n) const;
};

// split: {mode, train, validation} shares or {train_count, validation_count,
// test_count}; the fractions apply only without train_count, fractions and
// counts only with mode random (the default, left out of the resolved
// config).
const FieldList<SplitOptions>& split_fields();

struct Split {
  std::vector<std::size_t> train, validation, test;  // each sorted ascending
};

// A uniformly random partition: one Fisher-Yates shuffle of 0..n-1 with
// `rng` (n - 1 draws of rng.below), cut into SplitOptions::sizes(n): with
// fractions
//   n_train      = round(train_fraction * n),
//   n_validation = min(round(validation_fraction * n), n - n_train),
//   n_test       = n - n_train - n_validation,
// with round = std::llround (halves away from zero); with counts as given.
// Deterministic given the rng state; each part is sorted ascending.
Split make_random_split(std::size_t n, const SplitOptions& options, Rng& rng);

// The split `options.mode` says: make_random_split (drawing from `rng`), or
// the sequential halves (no draws).
Split make_split(std::size_t n, const SplitOptions& options, Rng& rng);

}  // namespace cnclab
