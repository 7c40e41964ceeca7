// The following_error generator's planning options (data/following_error.hpp):
// with them off the dataset and its identity are seed 002's; with
// feed_factors [1] it is the same data as seed 002's layout; a run at
// factor f is the plan in time u(f t) (closed form: tick 2j at f = 0.5 is
// tick j of the plan, at half the velocity); the halves, sequences and the
// direction inputs are where the header says.
#include <gtest/gtest.h>

#include <string>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/data/following_error.hpp"
#include "cnclab/data/generator.hpp"
#include "common/expect_error.hpp"

namespace cnclab {
namespace {

using testing::error_message;

// A short path (12 control points, 1.49 s at the limits), one unsmoothed
// run (the planning data's settings), 1200 samples of the plan kept.
std::shared_ptr<const DatasetGenerator> feeds_generator(const std::string& extra) {
  const std::string yaml =
      "dataset:\n  generator: following_error\n  options:\n"
      "    path: {control_points: 12}\n    runs: 1\n    smoothing: 1\n    samples: 1200\n" +
      extra;
  const ConfigDocument doc = ConfigDocument::parse(yaml, "test.yaml");
  auto g = read_generator(doc.root().section("dataset"));
  doc.check_all_consumed();
  return g;
}

Dataset generate(const std::string& extra) {
  Rng rng(11);
  return feeds_generator(extra)->generate(rng);
}

double meta(const Dataset& d, const char* name, Eigen::Index k) {
  return d.metadata(d.metadata_row(name), k);
}

TEST(FollowingErrorFeeds, OptionsOffKeepSeed002sIdentity) {
  // The identity text (options_yaml, hashed into the cache key) has none of
  // the new keys unless they are set.
  const std::string paper = feeds_generator("")->options_yaml();
  for (const char* key : {"feed_factors", "extra_inputs", "direction"}) {
    EXPECT_EQ(paper.find(key), std::string::npos) << key;
  }
  EXPECT_NE(feeds_generator("    feed_factors: [1]\n")->options_yaml().find("feed_factors"),
            std::string::npos);
  const Dataset d = generate("");
  EXPECT_EQ(d.metadata_row("feed_factor"), -1);
  EXPECT_EQ(d.metadata_row("sequence"), -1);
  EXPECT_EQ(d.input_names, (std::vector<std::string>{"v_x", "v_y"}));
}

TEST(FollowingErrorFeeds, FactorOneIsSeed002sData) {
  const Dataset paper = generate("");
  const Dataset one = generate("    feed_factors: [1]\n");
  ASSERT_EQ(one.num_samples(), paper.num_samples());
  EXPECT_EQ(one.inputs, paper.inputs);
  EXPECT_EQ(one.targets, paper.targets);
  const auto rows = static_cast<Eigen::Index>(paper.metadata_names.size());
  EXPECT_EQ(one.metadata.topRows(rows), paper.metadata);
  // Then the new columns: factor, sequence and piece (one piece: the whole plan).
  ASSERT_EQ(one.metadata_names.size(), paper.metadata_names.size() + 3);
  EXPECT_EQ(one.metadata_names[paper.metadata_names.size()], "feed_factor");
  EXPECT_EQ(one.metadata_names[paper.metadata_names.size() + 1], "sequence");
  EXPECT_EQ(one.metadata_names.back(), "piece");
  EXPECT_EQ(meta(one, "piece", 0), meta(one, "piece", 1199));
  // Two sequences: the first half (0), the second (1).
  EXPECT_EQ(meta(one, "sequence", 599), 0.0);
  EXPECT_EQ(meta(one, "sequence", 600), 1.0);
}

TEST(FollowingErrorFeeds, AHalfFeedRunIsThePlanAtHalfTheSpeed) {
  const Dataset d = generate("    feed_factors: [1, 0.5]\n");
  // Runs of 1200 (f = 1) and 2400 (f = 0.5) ticks: first halves [0, 600)
  // and [600, 1800), second halves [1800, 2400) and [2400, 3600).
  ASSERT_EQ(d.num_samples(), 3600u);
  EXPECT_EQ(first_validation_sample(d), 1800u);
  const auto plan_col = [](Eigen::Index j) { return j < 600 ? j : 1800 + j - 600; };
  const auto half_col = [](Eigen::Index k) { return k < 1200 ? 600 + k : 2400 + k - 1200; };
  for (Eigen::Index j = 0; j < 1200; j += 7) {
    const Eigen::Index p = plan_col(j), h = half_col(2 * j);
    ASSERT_NEAR(meta(d, "u", h), meta(d, "u", p), 1e-12) << j;
    for (const char* v : {"v_ref_x", "v_ref_y"}) {
      ASSERT_NEAR(meta(d, v, h), 0.5 * meta(d, v, p), 1e-9) << j;
    }
    ASSERT_EQ(meta(d, "feed_factor", p), 1.0);
    ASSERT_EQ(meta(d, "feed_factor", h), 0.5);
  }
  for (Eigen::Index k = 0; k < 3600; ++k) {
    ASSERT_EQ(meta(d, "validation", k), k >= 1800 ? 1.0 : 0.0) << k;
  }
  EXPECT_EQ(meta(d, "sequence", 0), 0.0);
  EXPECT_EQ(meta(d, "sequence", 600), 1.0);
  EXPECT_EQ(meta(d, "sequence", 1800), 2.0);
  EXPECT_EQ(meta(d, "sequence", 2400), 3.0);
  // The slower run lags less: a smaller largest following error.
  const Eigen::Index ex = d.metadata_row("e_ref_x");
  EXPECT_LT(d.metadata.row(ex).segment(600, 1200).cwiseAbs().maxCoeff(),
            d.metadata.row(ex).head(600).cwiseAbs().maxCoeff());
}

TEST(FollowingErrorFeeds, DirectionInputsFollowEachRunFromRest) {
  const Dataset d = generate(
      "    feed_factors: [1, 0.5]\n    extra_inputs: [direction, reversal]\n"
      "    direction: {reversal_time_constant: 0.01}\n");
  EXPECT_EQ(d.input_names, (std::vector<std::string>{"v_x", "v_y", "direction_x", "direction_y",
                                                     "reversal_x", "reversal_y"}));
  AxisDirectionOptions o;
  o.reversal_time_constant = 0.01;
  // Run f = 0.5: samples [600, 1800) then [2400, 3600), from rest.
  for (int a = 0; a < 2; ++a) {
    const char* v = a == 0 ? "v_ref_x" : "v_ref_y";
    std::vector<double> run;
    std::vector<Eigen::Index> cols;
    for (Eigen::Index k = 0; k < 2400; ++k) {
      cols.push_back(k < 1200 ? 600 + k : 2400 + k - 1200);
      run.push_back(meta(d, v, cols.back()));
    }
    const auto f = axis_direction_series(run, {AxisFeature::direction, AxisFeature::reversal}, o);
    for (std::size_t k = 0; k < run.size(); ++k) {
      ASSERT_EQ(d.inputs(2 + a, cols[k]), f[0][k]) << k;
      ASSERT_EQ(d.inputs(4 + a, cols[k]), f[1][k]) << k;
    }
  }
}

// plan_length: the path planned in pieces from rest to rest; the machine
// stops at every joint (a reference velocity of exactly 0 inside the run:
// round(length / 60 mm) pieces, a stop between each two), and the run is
// longer than the one plan of the whole path.
TEST(FollowingErrorFeeds, PiecesStopAtEveryJoint) {
  const Dataset whole = generate("");
  const Dataset pieces = generate("    plan_length: 60\n");
  const Eigen::Index vx = pieces.metadata_row("v_ref_x"), vy = pieces.metadata_row("v_ref_y");
  const Eigen::Index u = pieces.metadata_row("u");
  std::size_t stops = 0;
  for (Eigen::Index k = 1; k + 1 < 1200; ++k) {
    ASSERT_GE(pieces.metadata(u, k), pieces.metadata(u, k - 1)) << k;  // never backwards
    if (pieces.metadata(vx, k) == 0.0 && pieces.metadata(vy, k) == 0.0) ++stops;
  }
  EXPECT_GE(stops, 2u);
  // The same 1200 ticks cover less of the path when it stops on the way.
  EXPECT_LT(pieces.metadata(u, 1199), whole.metadata(u, 1199));
}

TEST(FollowingErrorFeeds, BadOptionsNameTheKey) {
  const auto message = [](const std::string& extra) {
    return error_message<ConfigError>([&] { feeds_generator(extra); });
  };
  EXPECT_NE(message("    feed_factors: [1, 1.5]\n").find("feed_factors"), std::string::npos);
  EXPECT_NE(message("    feed_factors: [0.5, 0.5]\n").find("twice"), std::string::npos);
  EXPECT_NE(message("    extra_inputs: [speed]\n").find("sign, direction or reversal"),
            std::string::npos);
  EXPECT_NE(message("    direction: {deadband: -1}\n").find("deadband"), std::string::npos);
  EXPECT_NE(message("    plan_length: -5\n").find("plan_length"), std::string::npos);
}

}  // namespace
}  // namespace cnclab
