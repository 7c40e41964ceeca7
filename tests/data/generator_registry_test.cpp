// The generator registry: a generator registered from above data/ (as a
// study's register function does) is read from a `dataset:` section,
// generates and caches like a built-in one; names are unique; and the
// built-in generators' dataset identities (the cache key) are those the
// built-in list gave before the registry (a cached dataset stays valid).
#include "cnclab/data/generator_registry.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/data/dataset_spec.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

// y = slope * x on x = 0, 1, ..., samples - 1: a generator a study might add.
class LineGenerator : public DatasetGenerator {
 public:
  LineGenerator(std::size_t samples, double slope) : samples_(samples), slope_(slope) {}
  std::string name() const override { return "registry_test_line"; }
  int version() const override { return 1; }
  DatasetShape shape() const override { return {samples_, 1, 1}; }
  std::string options_yaml() const override {
    return "samples: " + std::to_string(samples_) + "\nslope: " + std::to_string(slope_) + "\n";
  }
  Dataset generate(Rng&) const override {
    Dataset d;
    d.inputs.resize(1, static_cast<Eigen::Index>(samples_));
    for (std::size_t i = 0; i < samples_; ++i)
      d.inputs(0, static_cast<Eigen::Index>(i)) = double(i);
    d.targets = slope_ * d.inputs;
    d.input_names = {"x"};
    d.input_units = {"1"};
    d.target_names = {"y"};
    d.target_units = {"1"};
    d.generator = name();
    return d;
  }
  bool uses_seed() const override { return false; }

 private:
  std::size_t samples_;
  double slope_;
};

void register_line_once() {
  static bool done = false;  // the registry is process-wide: once per test binary
  if (done) return;
  done = true;
  register_generator({"registry_test_line", "a straight line (test)", [](const ConfigReader& r) {
                        const auto samples = r.get<std::size_t>("samples", 5);
                        const auto slope = r.get<double>("slope", 1.0);
                        return std::make_shared<LineGenerator>(samples, slope);
                      }});
}

DatasetSpec spec_of(const std::string& dataset_yaml) {
  const ConfigDocument doc = ConfigDocument::parse("dataset: " + dataset_yaml + "\n", "t.yaml");
  return read_dataset_spec(doc.root().section("dataset"));
}

TEST(GeneratorRegistry, ARegisteredGeneratorIsReadGeneratedAndCached) {
  register_line_once();
  const DatasetSpec spec =
      spec_of("{generator: registry_test_line, options: {samples: 4, slope: 2.5}}");
  ASSERT_TRUE(spec.generator);
  EXPECT_EQ(spec.generator->name(), "registry_test_line");
  testing::TempDir dir;
  const CachedDataset made = obtain_dataset(spec, 1, dir.path(), nullptr);
  ASSERT_EQ(made.dataset.targets.cols(), 4);
  EXPECT_DOUBLE_EQ(made.dataset.targets(0, 3), 7.5);                 // 2.5 * 3
  EXPECT_TRUE(obtain_dataset(spec, 2, dir.path(), nullptr).reused);  // ignores its seed
  const auto names = [] {
    std::vector<std::string> n;
    for (const auto& g : known_generators()) n.push_back(g.name);
    return n;
  }();
  // The built-in ones first, in their order, then the registered one.
  EXPECT_EQ(names, (std::vector<std::string>{"friedman1", "step_error", "ik_samples",
                                             "following_error", "registry_test_line"}));
}

TEST(GeneratorRegistry, NamesAreUniqueAndUnknownNamesListTheRegisteredOnes) {
  register_line_once();
  EXPECT_THROW(register_generator({"friedman1", "again", nullptr}), std::logic_error);
  EXPECT_THROW(register_generator({"registry_test_line", "again", nullptr}), std::logic_error);
  try {
    spec_of("{generator: registry_test_lin}");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("friedman1, step_error, ik_samples, following_error, registry_test_line"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("did you mean"), std::string::npos) << what;
  }
}

// A friedman1 dataset (50 samples) as `cnclab run` made it before the
// registry: the file name and the generator_config text stored in it (read
// with h5py from the file that build wrote; seed as that run derived it).
// The identity of every cached dataset is unchanged.
TEST(GeneratorRegistry, BuiltInDatasetIdentityUnchanged) {
  const DatasetSpec spec = spec_of("{generator: friedman1, options: {samples: 50}}");
  constexpr std::uint64_t kSeed = 15482501427895417148u;
  EXPECT_EQ(dataset_config_text(*spec.generator, kSeed),
            "samples: 50\ninputs: 10\nnoise_std: 1\ngenerator_version: 1\n"
            "seed: 15482501427895417148\n");
  EXPECT_EQ(dataset_cache_file(spec, kSeed, "d").filename().string(),
            "friedman1-bc06c8d7041792b9.h5");
}

}  // namespace
}  // namespace cnclab
