#include "cnclab/data/friedman1.hpp"

#include <cmath>
#include <numbers>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/resources.hpp"
#include "cnclab/data/declared_generator.hpp"

namespace cnclab {

const FieldList<Friedman1Options>& friedman1_fields() {
  using O = Friedman1Options;
  static const auto fields =
      FieldList<O>()
          .field("samples", &O::samples, "number of samples", Rule::in(1, true, 1e8, true))
          .field("inputs", &O::inputs, "d: x1..x5 enter y, x6..xd are noise features",
                 Rule::in(5, true, 10000, true))
          .field("noise_std", &O::noise_std, "standard deviation of eps ~ N(0, noise_std²)",
                 Rule::non_negative());
  return fields;
}

void Friedman1Options::validate() const {
  if (samples < 1) throw OptionError("samples", std::to_string(samples), "must be at least 1");
  if (samples > 100'000'000) {
    throw OptionError("samples", std::to_string(samples), "must be at most 100000000");
  }
  if (inputs < 5 || inputs > 10'000) {
    throw OptionError("inputs", std::to_string(inputs), "must be in [5, 10000] (x1..x5 enter y)");
  }
  if (!(noise_std >= 0.0) || !std::isfinite(noise_std)) {
    throw OptionError("noise_std", std::to_string(noise_std), "must be a finite number >= 0");
  }
}

double friedman1_function(const double* x) {
  return 10.0 * std::sin(std::numbers::pi * x[0] * x[1]) + 20.0 * (x[2] - 0.5) * (x[2] - 0.5) +
         10.0 * x[3] + 5.0 * x[4];
}

Dataset generate_friedman1(const Friedman1Options& options, Rng& rng) {
  options.validate();
  check_memory(static_cast<double>(options.samples) * static_cast<double>(options.inputs + 1) * 8.0,
               "friedman1 dataset (" + std::to_string(options.samples) + " samples x " +
                   std::to_string(options.inputs + 1) + " values)");
  Dataset d;
  const auto n = static_cast<Eigen::Index>(options.samples);
  const auto dim = static_cast<Eigen::Index>(options.inputs);
  d.inputs.resize(dim, n);
  d.targets.resize(1, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < dim; ++i) d.inputs(i, j) = rng.uniform();
    d.targets(0, j) = friedman1_function(&d.inputs(0, j)) + options.noise_std * rng.normal();
  }
  for (std::size_t i = 1; i <= options.inputs; ++i) {
    d.input_names.push_back(std::string(1, 'x').append(std::to_string(i)));
  }
  d.input_units.assign(options.inputs, "1");
  d.target_names = {"y"};
  d.target_units = {"1"};
  d.generator = "friedman1";
  return d;
}

Friedman1Generator::Friedman1Generator(Friedman1Options options) : options_(options) {
  options_.validate();
}

std::string Friedman1Generator::options_yaml() const {
  return friedman1_fields().yaml(options_);
}

std::shared_ptr<const DatasetGenerator> read_friedman1(const ConfigReader& r) {
  return read_declared_generator<Friedman1Generator>(r, friedman1_fields());
}

}  // namespace cnclab
