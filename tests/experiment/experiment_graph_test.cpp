// Dependency order, cycles, and the staleness rule of the experiment graph.
#include "cnclab/experiment/experiment_graph.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "cnclab/core/error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& p, const std::string& name, const std::string& extra) {
  std::ofstream(p)
      << "name: " << name
      << "\nseed: 1\ndataset: {generator: friedman1}\nmodel: {}\ntrainer: {type: sgdm}\n"
      << extra;
}

TEST(ExperimentGraph, UpstreamComesFirstAndIsAddedWhenNotRequested) {
  testing::TempDir dir;
  write(dir / "a.yaml", "a", "");
  write(dir / "b.yaml", "b", "init_from: {experiment: a.yaml}\n");
  write(dir / "c.yaml", "c", "needs: [b.yaml, a.yaml]\n");
  const auto graph = load_graph({dir / "c.yaml"});
  ASSERT_EQ(graph.size(), 3u);
  EXPECT_EQ(graph[0].experiment->spec.name, "a");
  EXPECT_EQ(graph[1].experiment->spec.name, "b");
  EXPECT_EQ(graph[2].experiment->spec.name, "c");
  EXPECT_FALSE(graph[0].requested);
  EXPECT_TRUE(graph[2].requested);
  EXPECT_EQ(graph[2].upstream, (std::vector<std::size_t>{1, 0}));
  // Requesting a file twice (by another path) gives one node.
  EXPECT_EQ(load_graph({dir / "a.yaml", dir / "sub/../a.yaml"}).size(), 1u);
}

TEST(ExperimentGraph, CycleIsAConfigErrorNamingTheFiles) {
  testing::TempDir dir;
  write(dir / "a.yaml", "a", "needs: [b.yaml]\n");
  write(dir / "b.yaml", "b", "needs: [a.yaml]\n");
  try {
    load_graph({dir / "a.yaml"});
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("cycle"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("b.yaml"), std::string::npos);
  }
}

TEST(ExperimentGraph, AResultIsStaleWhenAnUpstreamIdentityChanged) {
  const std::vector<UpstreamRef> r = {{"a.yaml", "results/a/a.h5", "1111"}};
  EXPECT_EQ(staleness(r, {{"a", "1111"}}), "");
  EXPECT_EQ(staleness(r, {{"a", "2222"}}), "upstream a changed");
  EXPECT_EQ(staleness(r, {}), "its upstream experiments changed");
  EXPECT_EQ(staleness({}, {{"a", "1111"}}), "upstream a changed");
}

}  // namespace
}  // namespace cnclab
