#include "cnclab/data/split.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "cnclab/core/error.hpp"

namespace cnclab {

void SplitOptions::validate() const {
  if (!(train_fraction > 0.0 && train_fraction <= 1.0)) {
    throw OptionError("train_fraction", std::to_string(train_fraction), "must be in (0, 1]");
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

Split make_random_split(std::size_t n, const SplitOptions& options, Rng& rng) {
  options.validate();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  rng.shuffle(order);
  const auto n_train = std::min(
      n, static_cast<std::size_t>(std::llround(options.train_fraction * static_cast<double>(n))));
  const auto n_val = std::min(
      n - n_train,
      static_cast<std::size_t>(std::llround(options.validation_fraction * static_cast<double>(n))));
  Split s;
  s.train.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n_train));
  s.validation.assign(order.begin() + static_cast<std::ptrdiff_t>(n_train),
                      order.begin() + static_cast<std::ptrdiff_t>(n_train + n_val));
  s.test.assign(order.begin() + static_cast<std::ptrdiff_t>(n_train + n_val), order.end());
  for (auto* part : {&s.train, &s.validation, &s.test}) std::sort(part->begin(), part->end());
  return s;
}

}  // namespace cnclab
