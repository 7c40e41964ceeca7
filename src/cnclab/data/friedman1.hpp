#pragma once
// Friedman #1 regression benchmark (J. H. Friedman, "Multivariate adaptive
// regression splines", Ann. Statist. 19(1), 1991):
//   y = 10 sin(pi x1 x2) + 20 (x3 - 0.5)^2 + 10 x4 + 5 x5 + eps,
//   x ~ U[0, 1)^d (d >= 5; x6..xd are noise features), eps ~ N(0, noise_std^2).
#include <cstddef>
#include <string>

#include "cnclab/core/fields.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/dataset.hpp"
#include "cnclab/data/generator.hpp"

namespace cnclab {

struct Friedman1Options {
  std::size_t samples = 1000;
  std::size_t inputs = 10;  // d >= 5
  double noise_std = 1.0;   // standard deviation of eps, >= 0
  void validate() const;
};

// dataset.options of `friedman1`: {samples, inputs, noise_std}.
const FieldList<Friedman1Options>& friedman1_fields();

// The noise-free function value.
double friedman1_function(const double* x);

Dataset generate_friedman1(const Friedman1Options& options, Rng& rng);

// The registered generator `friedman1`: options {samples, inputs, noise_std}.
class Friedman1Generator : public DatasetGenerator {
 public:
  explicit Friedman1Generator(Friedman1Options options);  // validates
  std::string name() const override { return "friedman1"; }
  int version() const override { return 1; }
  DatasetShape shape() const override { return {options_.samples, options_.inputs, 1}; }
  std::string options_yaml() const override;
  Dataset generate(Rng& rng) const override { return generate_friedman1(options_, rng); }

 private:
  Friedman1Options options_;
};

std::shared_ptr<const DatasetGenerator> read_friedman1(const ConfigReader& options);

}  // namespace cnclab
