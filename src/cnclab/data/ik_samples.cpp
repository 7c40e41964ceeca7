#include "cnclab/data/ik_samples.hpp"

#include <array>
#include <cmath>
#include <numeric>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/resources.hpp"
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

std::string to_string(SamplingMode m) {
  return m == SamplingMode::grid      ? "grid"
         : m == SamplingMode::uniform ? "uniform"
                                      : "latin_hypercube";
}

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

std::string IkSamplesGenerator::options_yaml() const {
  const IkSamplesOptions& o = options_;
  std::string s = "mode: " + to_string(o.mode) + "\n";
  if (o.mode == SamplingMode::grid) {
    s += "values_per_input: " + std::to_string(o.values_per_input) + "\n";
  } else {
    s += "samples: " + std::to_string(o.samples) + "\n";
  }
  s += "ranges: {px: " + range_text(o.px) + ", py: " + range_text(o.py) +
       ", pz: " + range_text(o.pz) + ", oi: " + range_text(o.oi) + ", oj: " + range_text(o.oj) +
       "}\n";
  s += "a_branch: " + to_string(o.branch) + "\nmachine:\n";
  const std::string machine = tttrr_options_yaml(o.machine);
  std::size_t start = 0;
  while (start < machine.size()) {
    const auto end = machine.find('\n', start);
    s += "  " + machine.substr(start, end - start) + "\n";
    start = end == std::string::npos ? machine.size() : end + 1;
  }
  return s;
}

std::shared_ptr<const DatasetGenerator> read_ik_samples(const ConfigReader& r) {
  IkSamplesOptions o;
  const auto mode = r.get<std::string>("mode", to_string(o.mode));
  if (mode == "grid") {
    o.mode = SamplingMode::grid;
    o.values_per_input = r.get<std::size_t>("values_per_input", o.values_per_input);
  } else if (mode == "uniform" || mode == "latin_hypercube") {
    o.mode = mode == "uniform" ? SamplingMode::uniform : SamplingMode::latin_hypercube;
    o.samples = r.get<std::size_t>("samples", o.samples);
  } else {
    r.fail("mode", "must be one of: grid, uniform, latin_hypercube");
  }
  const ConfigReader ranges = r.section("ranges");
  const char* keys[] = {"px", "py", "pz", "oi", "oj"};
  JointRange* fields[] = {&o.px, &o.py, &o.pz, &o.oi, &o.oj};
  for (int i = 0; i < kInputs; ++i) {
    if (!ranges.has(keys[i])) continue;
    const auto v = ranges.require<std::vector<double>>(keys[i]);
    if (v.size() != 2) ranges.fail(keys[i], "must be a list [min, max]");
    *fields[i] = {v[0], v[1]};
  }
  const auto branch = r.get<std::string>("a_branch", to_string(o.branch));
  if (branch != "positive" && branch != "negative") {
    r.fail("a_branch", "must be one of: positive, negative");
  }
  o.branch = branch == "positive" ? ABranch::positive : ABranch::negative;
  o.machine = read_tttrr_options(r.section("machine"));
  r.validate([&] { o.validate(); });
  return std::make_shared<IkSamplesGenerator>(o);
}

}  // namespace cnclab
