// The LM core on NIST StRD certified nonlinear regression problems
// (https://www.itl.nist.gov/div898/strd/nls/nls_main.shtml): from both of
// NIST's starting points the parameters must match the certified values to
// at least 6 significant digits. Data files: tests/train/data/nist/.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "cnclab/train/lm.hpp"

namespace cnclab {
namespace {

// 6 significant digits: relative error below half a unit in the 6th digit.
constexpr double kSixDigits = 5e-7;

struct NistProblem {
  std::vector<double> x, y, start1, start2, certified;
  double certified_rss = 0;
};

std::vector<double> numbers(std::istringstream& in) {
  std::vector<double> v;
  for (double d; in >> d;) v.push_back(d);
  return v;
}

NistProblem load(const std::string& name) {
  const std::string path = std::string(CNCLAB_SOURCE_DIR) + "/tests/train/data/nist/" + name;
  std::ifstream file(path);
  EXPECT_TRUE(file) << path;
  NistProblem p;
  for (std::string line; std::getline(file, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream in(line);
    std::string key;
    if (std::isalpha(static_cast<unsigned char>(line[0]))) in >> key;
    const auto v = numbers(in);
    if (key == "start1")
      p.start1 = v;
    else if (key == "start2")
      p.start2 = v;
    else if (key == "certified")
      p.certified = v;
    else if (key == "certified_rss")
      p.certified_rss = v.at(0);
    else {
      EXPECT_EQ(v.size(), 2u) << line;
      p.y.push_back(v.at(0));
      p.x.push_back(v.at(1));
    }
  }
  return p;
}

// Residual e_i = f(x_i; b) - y_i with the model's analytic gradient in b.
using Model =
    std::function<double(double x, const Eigen::VectorXd& b, Eigen::Ref<Eigen::RowVectorXd> grad)>;

class CurveFit : public ResidualObjective {
 public:
  CurveFit(const NistProblem& p, Model model) : p_(p), model_(std::move(model)) {}
  Eigen::Index num_residuals() const override { return static_cast<Eigen::Index>(p_.x.size()); }
  Eigen::Index num_parameters() const override {
    return static_cast<Eigen::Index>(p_.certified.size());
  }
  void evaluate(const Eigen::VectorXd& b, Eigen::Index first, Eigen::Index count,
                Eigen::Ref<Eigen::VectorXd> e, Eigen::MatrixXd* jacobian) override {
    Eigen::RowVectorXd grad(b.size());
    for (Eigen::Index r = 0; r < count; ++r) {
      const auto i = static_cast<std::size_t>(first + r);
      e[r] = model_(p_.x[i], b, grad) - p_.y[i];
      if (jacobian) jacobian->row(r) = grad;
    }
  }

 private:
  const NistProblem& p_;
  Model model_;
};

void expect_certified(const std::string& file, const Model& model) {
  const NistProblem p = load(file);
  ASSERT_EQ(p.start1.size(), p.certified.size());
  ASSERT_EQ(p.start2.size(), p.certified.size());
  for (const auto& start : {p.start1, p.start2}) {
    CurveFit fit(p, model);
    Eigen::VectorXd b =
        Eigen::Map<const Eigen::VectorXd>(start.data(), static_cast<Eigen::Index>(start.size()));
    LmOptions o;         // trainlm defaults
    o.min_gradient = 0;  // run to the rounding floor (mu_max) or the epoch limit
    o.epochs = 5000;
    const Summary s = train_lm(fit, b, o);
    const std::string where = file + " from start " + (start == p.start1 ? "1" : "2") + " (" +
                              to_string(s.termination) + ": " + s.message + ")";
    EXPECT_NE(s.termination, Termination::diverged) << where;
    for (std::size_t j = 0; j < p.certified.size(); ++j) {
      const double c = p.certified[j], got = b[static_cast<Eigen::Index>(j)];
      EXPECT_LE(std::abs(got - c), kSixDigits * std::abs(c))
          << where << ": b" << j + 1 << " = " << got << ", certified " << c;
    }
    EXPECT_NEAR(s.lm_history.back().sse, p.certified_rss, kSixDigits * p.certified_rss) << where;
  }
}

// y = b1 (1 - exp(-b2 x)): Misra1a and BoxBOD.
double exponential_rise(double x, const Eigen::VectorXd& b, Eigen::Ref<Eigen::RowVectorXd> g) {
  const double e = std::exp(-b[1] * x);
  g[0] = 1 - e;
  g[1] = b[0] * x * e;
  return b[0] * (1 - e);
}

TEST(NistStrd, Misra1a) {
  expect_certified("misra1a.txt", exponential_rise);
}

double rational(double x, const Eigen::VectorXd& b, Eigen::Ref<Eigen::RowVectorXd> g) {
  const double num = b[0] + x * (b[1] + x * (b[2] + x * b[3]));
  const double den = 1 + x * (b[4] + x * (b[5] + x * b[6]));
  double xp = 1;
  for (int j = 0; j < 4; ++j, xp *= x) g[j] = xp / den;
  xp = x;
  for (int j = 4; j < 7; ++j, xp *= x) g[j] = -num * xp / (den * den);
  return num / den;
}

TEST(NistStrd, Thurber) {
  expect_certified("thurber.txt", rational);
}

TEST(NistStrd, Mgh09) {
  expect_certified("mgh09.txt", [](double x, const Eigen::VectorXd& b, auto g) {
    const double num = x * x + x * b[1], den = x * x + x * b[2] + b[3];
    g[0] = num / den;
    g[1] = b[0] * x / den;
    g[2] = -b[0] * num * x / (den * den);
    g[3] = -b[0] * num / (den * den);
    return b[0] * num / den;
  });
}

TEST(NistStrd, BoxBod) {
  expect_certified("boxbod.txt", exponential_rise);
}

TEST(NistStrd, Rat43) {
  expect_certified("rat43.txt", [](double x, const Eigen::VectorXd& b, auto g) {
    const double e = std::exp(b[1] - b[2] * x), base = 1 + e, p = -1 / b[3];
    const double f = b[0] * std::pow(base, p);
    g[0] = std::pow(base, p);
    g[1] = b[0] * p * std::pow(base, p - 1) * e;
    g[2] = -b[0] * p * std::pow(base, p - 1) * e * x;
    g[3] = f * std::log(base) / (b[3] * b[3]);
    return f;
  });
}

}  // namespace
}  // namespace cnclab
