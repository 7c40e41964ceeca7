#include "cnclab/data/ik_samples.hpp"

#include <array>
#include <cmath>
#include <numeric>
#include <tuple>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/resources.hpp"
#include "cnclab/data/declared_generator.hpp"
#include "cnclab/kinematics/tttrr_config.hpp"

namespace cnclab {
namespace {

constexpr std::size_t kMaxSamples = 100'000'000;
constexpr int kInputs = 5;

std::string range_text(const JointRange& r) {
  std::string text = "[";
  text += shortest_double(r.min);
  text += ", ";
  text += shortest_double(r.max);
  return text += "]";
}

std::array<const JointRange*, kInputs> ranges(const IkSamplesOptions& o) {
  return {&o.px, &o.py, &o.pz, &o.oi, &o.oj};
}
constexpr std::array<const char*, kInputs> kRangeKeys = {"ranges.px", "ranges.py", "ranges.pz",
                                                         "ranges.oi", "ranges.oj"};

}  // namespace

std::size_t IkSamplesOptions::num_samples() const {
  if (mode != SamplingMode::grid) return samples;
  double n = 1;
  for (int i = 0; i < kInputs; ++i) n *= static_cast<double>(values_per_input);
  return n > static_cast<double>(kMaxSamples) ? kMaxSamples + 1 : static_cast<std::size_t>(n);
}

void IkSamplesOptions::validate() const {
  if (mode == SamplingMode::grid) {
    if (values_per_input < 2) {
      throw OptionError("values_per_input", std::to_string(values_per_input), "must be at least 2");
    }
  } else if (samples < 1) {
    throw OptionError("samples", std::to_string(samples), "must be at least 1");
  }
  if (num_samples() > kMaxSamples) {
    throw OptionError(mode == SamplingMode::grid ? "values_per_input" : "samples",
                      std::to_string(mode == SamplingMode::grid ? values_per_input : samples),
                      "gives more than 100000000 samples");
  }
  const auto r = ranges(*this);
  for (int i = 0; i < kInputs; ++i) {
    if (!std::isfinite(r[i]->min) || !std::isfinite(r[i]->max) || !(r[i]->min < r[i]->max)) {
      throw OptionError(kRangeKeys[i], range_text(*r[i]), "must be finite with min < max");
    }
  }
  const double oi_max = std::max(std::abs(oi.min), std::abs(oi.max));
  const double oj_max = std::max(std::abs(oj.min), std::abs(oj.max));
  if (oi_max * oi_max + oj_max * oj_max > 1.0) {
    throw OptionError("ranges.oi", range_text(oi),
                      "with ranges.oj " + range_text(oj) +
                          " gives Oi^2 + Oj^2 > 1 (not a unit orientation vector)");
  }
  try {
    machine.validate();
  } catch (const OptionError& e) {
    throw OptionError("machine." + e.field(), e.value(), e.rule());
  }
}

Dataset generate_ik_samples(const IkSamplesOptions& o, Rng& rng) {
  o.validate();
  const std::size_t n = o.num_samples();
  check_memory(static_cast<double>(n) * 10.0 * 8.0,
               "ik_samples dataset (" + std::to_string(n) + " samples x 10 values)");
  const auto r = ranges(o);
  const auto cols = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd x(kInputs, cols);
  if (o.mode == SamplingMode::grid) {
    const std::size_t v = o.values_per_input;
    for (std::size_t j = 0; j < n; ++j) {
      std::size_t rest = j;
      for (int i = kInputs - 1; i >= 0; --i) {  // last input fastest
        const double k = static_cast<double>(rest % v);
        rest /= v;
        x(i, static_cast<Eigen::Index>(j)) =
            r[i]->min + (r[i]->max - r[i]->min) * k / static_cast<double>(v - 1);
      }
    }
  } else if (o.mode == SamplingMode::uniform) {
    for (Eigen::Index j = 0; j < cols; ++j)
      for (int i = 0; i < kInputs; ++i) x(i, j) = rng.uniform(r[i]->min, r[i]->max);
  } else {
    std::vector<std::size_t> strata(n);
    for (int i = 0; i < kInputs; ++i) {
      std::iota(strata.begin(), strata.end(), std::size_t{0});
      rng.shuffle(strata);
      for (std::size_t j = 0; j < n; ++j) {
        const double u = (static_cast<double>(strata[j]) + rng.uniform()) / static_cast<double>(n);
        x(i, static_cast<Eigen::Index>(j)) = r[i]->min + (r[i]->max - r[i]->min) * u;
      }
    }
  }

  const TttrrMachine machine(o.machine);
  Dataset d;
  d.inputs = x;
  d.targets.resize(5, cols);
  for (Eigen::Index j = 0; j < cols; ++j) {
    ToolPose pose;
    pose.position = x.col(j).head<3>();
    const double oi = x(3, j), oj = x(4, j);
    pose.orientation = {oi, oj, std::sqrt(std::max(0.0, 1.0 - oi * oi - oj * oj))};
    try {
      const Joints q = machine.inverse(pose, o.branch);
      d.targets.col(j) << q.x, q.y, q.z, q.a, q.c;
    } catch (const KinematicsError& e) {
      throw ConfigError("ik_samples: sample " + std::to_string(j) + " (Px " +
                        shortest_double(x(0, j)) + ", Py " + shortest_double(x(1, j)) + ", Pz " +
                        shortest_double(x(2, j)) + " mm, Oi " + shortest_double(oi) + ", Oj " +
                        shortest_double(oj) + ") is unreachable: " + e.what() +
                        "; narrow the ranges or widen the machine's limits");
    }
  }
  d.input_names = {"Px", "Py", "Pz", "Oi", "Oj"};
  d.input_units = {"mm", "mm", "mm", "1", "1"};
  d.target_names = {"X", "Y", "Z", "A", "C"};
  d.target_units = {"mm", "mm", "mm", "rad", "rad"};
  d.generator = "ik_samples";
  return d;
}

IkSamplesGenerator::IkSamplesGenerator(IkSamplesOptions options) : options_(std::move(options)) {
  options_.validate();
}

const FieldList<IkSamplesOptions>& ik_samples_fields() {
  using O = IkSamplesOptions;
  static const auto ranges = [] {
    FieldList<O> f;
    for (const auto& [key, member, doc] : {std::tuple{"px", &O::px, "P_x [mm]"},
                                           {"py", &O::py, "P_y [mm]"},
                                           {"pz", &O::pz, "P_z [mm]"},
                                           {"oi", &O::oi, "O_i (Oi^2 + Oj^2 <= 1 at every corner)"},
                                           {"oj", &O::oj, "O_j"}}) {
      f = with_joint_range(std::move(f), key, member, 1.0, doc);
    }
    return f;
  }();
  static const auto fields =
      FieldList<O>()
          .choice("mode", &O::mode,
                  {{"grid", SamplingMode::grid},
                   {"uniform", SamplingMode::uniform},
                   {"latin_hypercube", SamplingMode::latin_hypercube}},
                  "how the input box is sampled (seed 004: a 5^5 grid)")
          .field("values_per_input", &O::values_per_input,
                 "grid: values per input (seed 004: 5, so 3125 samples)", Rule::at_least(2))
          .when("mode", {"grid"})
          .field("samples", &O::samples, "uniform / latin_hypercube: sample count",
                 Rule::at_least(1))
          .when("mode", {"uniform", "latin_hypercube"})
          .group("ranges", ranges, "the input box, [min, max] per input (inclusive)")
          .choice("a_branch", &O::branch,
                  {{"positive", ABranch::positive}, {"negative", ABranch::negative}},
                  "sign of A in the targets (seed 004 Eq. 5's +-)")
          .section("machine", &O::machine, tttrr_fields(),
                   "the TTTRR machine (configs/machines/tttrr_*.yaml keys)");
  return fields;
}

std::string IkSamplesGenerator::options_yaml() const {
  return ik_samples_fields().yaml(options_);
}

std::shared_ptr<const DatasetGenerator> read_ik_samples(const ConfigReader& r) {
  return read_declared_generator<IkSamplesGenerator>(r, ik_samples_fields());
}

}  // namespace cnclab
