#include "cnclab/data/friedman1.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/data/generator.hpp"

namespace cnclab {
namespace {

// Friedman (1991), evaluated here independently of the library.
double friedman(const Eigen::VectorXd& x) {
  return 10 * std::sin(std::numbers::pi * x(0) * x(1)) + 20 * std::pow(x(2) - 0.5, 2) + 10 * x(3) +
         5 * x(4);
}

constexpr double kFormulaTol = 1e-12;

TEST(Friedman1, NoiseFreeTargetsEqualTheFormula) {
  Rng rng(3);
  const Dataset d = generate_friedman1({500, 7, 0.0}, rng);
  ASSERT_EQ(d.inputs.rows(), 7);
  ASSERT_EQ(d.inputs.cols(), 500);
  ASSERT_EQ(d.targets.rows(), 1);
  for (Eigen::Index j = 0; j < d.inputs.cols(); ++j) {
    const Eigen::VectorXd x = d.inputs.col(j);
    ASSERT_NEAR(d.targets(0, j), friedman(x), kFormulaTol);
    ASSERT_TRUE((x.array() >= 0).all() && (x.array() < 1).all());
  }
  EXPECT_NO_THROW(d.validate());
}

TEST(Friedman1, NamesUnitsAndConfig) {
  Rng rng(3);
  const Dataset d = generate_friedman1({4, 6, 0.1}, rng);
  EXPECT_EQ(d.input_names, (std::vector<std::string>{"x1", "x2", "x3", "x4", "x5", "x6"}));
  EXPECT_EQ(d.input_units, std::vector<std::string>(6, "1"));
  EXPECT_EQ(d.target_names, std::vector<std::string>{"y"});
  EXPECT_EQ(d.target_units, std::vector<std::string>{"1"});
  EXPECT_EQ(d.generator, "friedman1");
}

// Residual y - f(x) is N(0, s^2): its mean is within 5 standard errors of 0
// and its sample std within 5 standard errors of s (se of the std of normal
// data ~ s / sqrt(2(n-1))).
TEST(Friedman1, NoiseHasTheConfiguredStd) {
  constexpr std::size_t kN = 20000;
  constexpr double kStd = 2.0;
  Rng rng(4);
  const Dataset d = generate_friedman1({kN, 5, kStd}, rng);
  Eigen::VectorXd residual(kN);
  for (Eigen::Index j = 0; j < d.inputs.cols(); ++j) {
    residual(j) = d.targets(0, j) - friedman(d.inputs.col(j));
  }
  const double mean = residual.mean();
  const double std = std::sqrt((residual.array() - mean).square().sum() / (kN - 1));
  EXPECT_NEAR(mean, 0.0, 5 * kStd / std::sqrt(kN));
  EXPECT_NEAR(std, kStd, 5 * kStd / std::sqrt(2.0 * (kN - 1)));
}

// x ~ U[0, 1): every input's mean is within 5 standard errors of 1/2
// (variance of U[0,1) is 1/12).
TEST(Friedman1, InputsAreUniform) {
  constexpr std::size_t kN = 5000;
  Rng rng(8);
  const Dataset d = generate_friedman1({kN, 10, 1.0}, rng);
  for (Eigen::Index i = 0; i < d.inputs.rows(); ++i) {
    EXPECT_NEAR(d.inputs.row(i).mean(), 0.5, 5 * std::sqrt(1.0 / 12.0 / kN)) << i;
  }
}

TEST(Friedman1, SameSeedSameDataset) {
  Rng a(11), b(11), c(12);
  const Friedman1Options o{50, 5, 1.0};
  EXPECT_EQ(generate_friedman1(o, a).content_hash(), generate_friedman1(o, b).content_hash());
  EXPECT_NE(generate_friedman1(o, a).content_hash(), generate_friedman1(o, c).content_hash());
}

TEST(Friedman1, OptionsValidated) {
  try {
    Friedman1Options{10, 4, 1.0}.validate();
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "inputs");
    EXPECT_EQ(e.value(), "4");
  }
  EXPECT_THROW((Friedman1Options{10, 5, -1.0}.validate()), OptionError);
  EXPECT_THROW((Friedman1Options{10, 5, std::nan("")}.validate()), OptionError);
  EXPECT_THROW((Friedman1Options{0, 5, 1.0}.validate()), OptionError);
  EXPECT_NO_THROW((Friedman1Options{}.validate()));
  Rng rng(1);
  EXPECT_THROW(generate_friedman1({10, 4, 1.0}, rng), OptionError);
}

// The registry reads the options strictly, and options_yaml() is the resolved
// config that reads back to the same generator.
TEST(Friedman1, RegistryReadsOptionsAndRoundTripsThem) {
  const ConfigDocument doc = ConfigDocument::parse(
      "generator: friedman1\noptions: {samples: 4, inputs: 6, noise_std: 0.1}\n", "test");
  const auto generator = read_generator(doc.root());
  EXPECT_EQ(generator->name(), "friedman1");
  EXPECT_EQ(generator->options_yaml(), "samples: 4\ninputs: 6\nnoise_std: 0.1\n");
  const DatasetShape shape = generator->shape();
  EXPECT_EQ(shape.samples, 4u);
  EXPECT_EQ(shape.inputs, 6u);
  EXPECT_EQ(shape.outputs, 1u);

  const ConfigDocument again =
      ConfigDocument::parse("generator: friedman1\noptions:\n" +
                                std::string("  samples: 4\n  inputs: 6\n  noise_std: 0.1\n"),
                            "again");
  EXPECT_EQ(read_generator(again.root())->options_yaml(), generator->options_yaml());

  Rng a(5), b(5);
  EXPECT_EQ(generator->generate(a).content_hash(),
            generate_friedman1({4, 6, 0.1}, b).content_hash());
}

TEST(Friedman1, RegistryRejectsUnknownGeneratorsAndOptions) {
  const auto message = [](const std::string& yaml) {
    try {
      const ConfigDocument doc = ConfigDocument::parse(yaml, "t.yaml");
      read_generator(doc.root());
      doc.check_all_consumed();
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(
      message("generator: friedman2\n").find("generator = friedman2: must be one of: friedman1"),
      std::string::npos);
  EXPECT_NE(message("generator: friedman1\noptions: {inputs: 3}\n").find("options.inputs = 3"),
            std::string::npos);
  EXPECT_NE(message("generator: friedman1\noptions: {sample: 3}\n").find("unknown key"),
            std::string::npos);
  // No default generator: a forgotten one is an error, not friedman1.
  EXPECT_NE(message("options: {samples: 3}\n").find("generator: is required (one of: friedman1"),
            std::string::npos);
}

}  // namespace
}  // namespace cnclab
