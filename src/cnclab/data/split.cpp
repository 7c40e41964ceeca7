#include "cnclab/data/split.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "cnclab/core/error.hpp"

namespace cnclab {

const FieldList<SplitOptions>& split_fields() {
  using O = SplitOptions;
  const std::string both = "give either fractions (train, validation) or counts, not both";
  const std::string random_only = "applies to split.mode random only";
  static const auto fields =
      FieldList<O>()
          .choice(
              "mode", &O::mode,
              {{"random", SplitMode::random}, {"sequential_halves", SplitMode::sequential_halves}},
              "random: shares or counts drawn at random; sequential_halves: first half "
              "trains, second validates, in time order (seed 002; model.type narx)")
          .omit_default()
          .field("train_count", &O::train_count,
                 "training samples: counts instead of shares (seed 004: 1042)")
          .when("mode", {"random"}, random_only)
          .field("validation_count", &O::validation_count,
                 "validation samples; absent: the rest after test_count (or none)")
          .when("mode", {"random"}, random_only)
          .field("test_count", &O::test_count, "test samples; absent: the rest")
          .when("mode", {"random"}, random_only)
          .field("train", &O::train_fraction, "share of the samples for training (seed 000: 0.7)",
                 Rule::in(0, true, 1, true))
          .unless_set("train_count", both)
          .field("validation", &O::validation_fraction,
                 "share held out of training for early stopping; train + validation <= 1",
                 Rule::in(0, true, 1, false))
          .unless_set("train_count", both);
  return fields;
}

void SplitOptions::validate() const {
  if (uses_counts()) return;
  if (validation_count || test_count) {
    const char* field = validation_count ? "validation_count" : "test_count";
    throw OptionError(field, std::to_string(validation_count ? *validation_count : *test_count),
                      "needs train_count (counts replace the fractions)");
  }
  if (!(train_fraction >= 0.0 && train_fraction <= 1.0)) {
    throw OptionError("train_fraction", std::to_string(train_fraction), "must be in [0, 1]");
  }
  if (!(validation_fraction >= 0.0 && validation_fraction < 1.0)) {
    throw OptionError("validation_fraction", std::to_string(validation_fraction),
                      "must be in [0, 1)");
  }
  if (train_fraction + validation_fraction > 1.0 + 1e-12) {
    throw OptionError("validation_fraction", std::to_string(validation_fraction),
                      "train + validation must not exceed 1");
  }
}

void SplitOptions::validate_for(std::size_t n) const {
  validate();
  if (!uses_counts()) return;
  const std::size_t given = *train_count + validation_count.value_or(0) + test_count.value_or(0);
  const std::string rule =
      "train_count + validation_count + test_count = " + std::to_string(given) + " for " +
      std::to_string(n) + " samples";
  if (given > n) {
    const char* field = test_count         ? "test_count"
                        : validation_count ? "validation_count"
                                           : "train_count";
    throw OptionError(field,
                      std::to_string(test_count         ? *test_count
                                     : validation_count ? *validation_count
                                                        : *train_count),
                      rule + ": more than the samples");
  }
  if (validation_count && test_count && given != n) {
    throw OptionError("test_count", std::to_string(*test_count),
                      rule +
                          ": with all three counts given they must add up to the samples "
                          "(leave one out to give it the rest)");
  }
}

SplitOptions::Sizes SplitOptions::sizes(std::size_t n) const {
  if (mode == SplitMode::sequential_halves) return {n / 2, n - n / 2, 0};
  validate_for(n);
  Sizes s;
  if (uses_counts()) {
    s.train = *train_count;
    if (validation_count) {
      s.validation = *validation_count;
      s.test = n - s.train - s.validation;
    } else {
      s.test = test_count.value_or(n - s.train);
      s.validation = n - s.train - s.test;
    }
    return s;
  }
  s.train =
      std::min(n, static_cast<std::size_t>(std::llround(train_fraction * static_cast<double>(n))));
  s.validation = std::min(
      n - s.train,
      static_cast<std::size_t>(std::llround(validation_fraction * static_cast<double>(n))));
  s.test = n - s.train - s.validation;
  return s;
}

Split make_random_split(std::size_t n, const SplitOptions& options, Rng& rng) {
  const SplitOptions::Sizes sizes = options.sizes(n);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  rng.shuffle(order);
  const std::size_t n_train = sizes.train, n_val = sizes.validation;
  Split s;
  s.train.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n_train));
  s.validation.assign(order.begin() + static_cast<std::ptrdiff_t>(n_train),
                      order.begin() + static_cast<std::ptrdiff_t>(n_train + n_val));
  s.test.assign(order.begin() + static_cast<std::ptrdiff_t>(n_train + n_val), order.end());
  for (auto* part : {&s.train, &s.validation, &s.test}) std::sort(part->begin(), part->end());
  return s;
}

Split make_split(std::size_t n, const SplitOptions& options, Rng& rng) {
  if (options.mode == SplitMode::random) return make_random_split(n, options, rng);
  Split s;
  for (std::size_t i = 0; i < n; ++i) (i < n / 2 ? s.train : s.validation).push_back(i);
  return s;
}

}  // namespace cnclab
