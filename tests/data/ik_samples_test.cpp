#include "cnclab/data/ik_samples.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

constexpr double kTol = 1e-12;

Dataset sampled(SamplingMode mode, std::size_t samples, std::uint64_t seed) {
  IkSamplesOptions o;
  o.mode = mode;
  o.samples = samples;
  Rng rng(seed);
  return generate_ik_samples(o, rng);
}

// The grid of seed 004: 5 values per input -> 3125 samples, each input taking
// exactly its 5 equally spaced values, every combination once.
TEST(IkSamples, GridHasFiveToTheFiveDistinctPoses) {
  Rng rng(1);
  const IkSamplesOptions o;
  const Dataset d = generate_ik_samples(o, rng);
  ASSERT_EQ(d.num_samples(), 3125u);
  ASSERT_EQ(d.inputs.rows(), 5);
  ASSERT_EQ(d.targets.rows(), 5);
  const JointRange* r[] = {&o.px, &o.py, &o.pz, &o.oi, &o.oj};
  for (int i = 0; i < 5; ++i) {
    std::set<double> values;
    for (Eigen::Index j = 0; j < d.inputs.cols(); ++j) values.insert(d.inputs(i, j));
    ASSERT_EQ(values.size(), 5u) << i;
    EXPECT_EQ(*values.begin(), r[i]->min);
    EXPECT_NEAR(*values.rbegin(), r[i]->max, kTol);
  }
  std::set<std::vector<double>> poses;
  for (Eigen::Index j = 0; j < d.inputs.cols(); ++j) {
    poses.insert({d.inputs.col(j).data(), d.inputs.col(j).data() + 5});
  }
  EXPECT_EQ(poses.size(), 3125u);
  EXPECT_NO_THROW(d.validate());
  EXPECT_EQ(d.target_names, (std::vector<std::string>{"X", "Y", "Z", "A", "C"}));
  EXPECT_EQ(d.target_units, (std::vector<std::string>{"mm", "mm", "mm", "rad", "rad"}));
  EXPECT_EQ(d.input_units, (std::vector<std::string>{"mm", "mm", "mm", "1", "1"}));
}

// Targets against closed forms written here: A = +-asin(|(Oi, Oj)|) (Ok > 0),
// C = atan2(Oi, Oj) (positive branch), and the joints reproduce the pose.
TEST(IkSamples, TargetsAreTheInverseKinematicsOfTheInputs) {
  for (ABranch branch : {ABranch::positive, ABranch::negative}) {
    IkSamplesOptions o;
    o.mode = SamplingMode::uniform;
    o.samples = 500;
    o.branch = branch;
    Rng rng(4);
    const Dataset d = generate_ik_samples(o, rng);
    const TttrrMachine m(o.machine);
    const double sign = branch == ABranch::positive ? 1.0 : -1.0;
    for (Eigen::Index j = 0; j < d.inputs.cols(); ++j) {
      const double oi = d.inputs(3, j), oj = d.inputs(4, j);
      ASSERT_NEAR(d.targets(3, j), sign * std::asin(std::hypot(oi, oj)), 1e-12);
      if (branch == ABranch::positive) {
        ASSERT_NEAR(d.targets(4, j), std::atan2(oi, oj), 1e-12);
      }
      const Joints q{d.targets(0, j), d.targets(1, j), d.targets(2, j), d.targets(3, j),
                     d.targets(4, j)};
      const ToolPose p = m.forward(q);
      ASSERT_LT((p.position - d.inputs.col(j).head<3>()).cwiseAbs().maxCoeff(), 1e-9);
      ASSERT_NEAR(p.orientation.x(), oi, kTol);
      ASSERT_NEAR(p.orientation.y(), oj, kTol);
    }
  }
}

// Latin hypercube: each input has exactly one sample in each of the n equal
// strata of its range.
TEST(IkSamples, LatinHypercubeFillsEveryStratumOnce) {
  const Dataset d = sampled(SamplingMode::latin_hypercube, 200, 7);
  const IkSamplesOptions o;
  const JointRange* r[] = {&o.px, &o.py, &o.pz, &o.oi, &o.oj};
  for (int i = 0; i < 5; ++i) {
    std::vector<int> hits(200, 0);
    for (Eigen::Index j = 0; j < d.inputs.cols(); ++j) {
      const double u = (d.inputs(i, j) - r[i]->min) / (r[i]->max - r[i]->min);
      ++hits[static_cast<std::size_t>(std::min(199.0, std::floor(u * 200)))];
    }
    EXPECT_EQ(*std::min_element(hits.begin(), hits.end()), 1) << i;
    EXPECT_EQ(*std::max_element(hits.begin(), hits.end()), 1) << i;
  }
  EXPECT_EQ(sampled(SamplingMode::latin_hypercube, 200, 7).content_hash(), d.content_hash());
  EXPECT_NE(sampled(SamplingMode::latin_hypercube, 200, 8).content_hash(), d.content_hash());
}

TEST(IkSamples, BadOptionsAndUnreachablePosesAreClearErrors) {
  IkSamplesOptions o;
  o.oi = {0.5, 0.9};
  o.oj = {-0.5, 0.5};  // corner 0.9^2 + 0.5^2 > 1
  try {
    o.validate();
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "ranges.oi");
  }
  o = IkSamplesOptions{};
  o.values_per_input = 1;
  EXPECT_THROW(o.validate(), OptionError);
  o = IkSamplesOptions{};
  o.machine.x = {-10, 10};  // the work volume reaches X = +-50 mm and more
  Rng rng(1);
  try {
    generate_ik_samples(o, rng);
    FAIL();
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("ik_samples: sample 0"), std::string::npos) << m;
    EXPECT_NE(m.find("joint limit: X"), std::string::npos) << m;
  }
}

TEST(IkSamples, RegistryReadsOptionsAndRoundTripsThem) {
  const ConfigDocument doc = ConfigDocument::parse(
      "dataset:\n  generator: ik_samples\n  options:\n    mode: latin_hypercube\n"
      "    samples: 64\n    ranges: {pz: [-10, 10]}\n    a_branch: negative\n"
      "    machine: {offset_d: 80, limits: {a: [-90, 90]}}\n",
      "ik.yaml");
  const auto g = read_generator(doc.root().section("dataset"));
  EXPECT_EQ(g->name(), "ik_samples");
  EXPECT_EQ(g->shape().samples, 64u);
  const auto& o = dynamic_cast<const IkSamplesGenerator&>(*g).options();
  EXPECT_EQ(o.branch, ABranch::negative);
  EXPECT_EQ(o.pz.min, -10.0);
  EXPECT_EQ(o.machine.offset_d, 80.0);
  const ConfigDocument again = ConfigDocument::parse(
      "generator: ik_samples\noptions:\n" +
          [&] {
            std::string indented, line;
            for (char c : g->options_yaml()) {
              line += c;
              if (c == '\n') indented += "  " + line, line.clear();
            }
            return indented;
          }(),
      "again.yaml");
  EXPECT_EQ(read_generator(again.root())->options_yaml(), g->options_yaml());

  const ConfigDocument bad =
      ConfigDocument::parse("generator: ik_samples\noptions:\n  mode: sobol\n", "bad.yaml");
  EXPECT_THROW(read_generator(bad.root()), ConfigError);
}

TEST(SelectTargets, KeepsNamedRowsInOrderAndRejectsUnknownNames) {
  const Dataset d = sampled(SamplingMode::uniform, 10, 3);
  const Dataset s = select_targets(d, {"C", "X"});
  ASSERT_EQ(s.targets.rows(), 2);
  EXPECT_EQ(s.targets.row(0), d.targets.row(4));
  EXPECT_EQ(s.targets.row(1), d.targets.row(0));
  EXPECT_EQ(s.target_names, (std::vector<std::string>{"C", "X"}));
  EXPECT_EQ(s.target_units, (std::vector<std::string>{"rad", "mm"}));
  EXPECT_EQ(select_targets(d, {}).targets.rows(), 5);
  try {
    select_targets(d, {"Q"});
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("'Q' is not a target"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("X, Y, Z, A, C"), std::string::npos);
  }
  EXPECT_THROW(select_targets(d, {"X", "X"}), ConfigError);
}

}  // namespace
}  // namespace cnclab
