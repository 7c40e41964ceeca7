#include "cnclab/core/config.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {
namespace fs = std::filesystem;

// Runs f and returns the ConfigError message (fails the test if none).
template <class F>
std::string config_error(F&& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a ConfigError";
  return "";
}

// A temp dir with a helper to write files into it.
class TempDir : public testing::TempDir {
 public:
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = path() / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p;
  }
};

TEST(Config, TypedReadsAndDefaults) {
  auto doc = ConfigDocument::parse(
      "a: 1.5\nb: true\nc: hello\nd: 42\ne: [28, 20]\nf: 1e-4\nsec:\n  x: -3\n", "t.yaml");
  auto r = doc.root();
  EXPECT_DOUBLE_EQ(r.get<double>("a", 0), 1.5);
  EXPECT_TRUE(r.get<bool>("b", false));
  EXPECT_EQ(r.get<std::string>("c", ""), "hello");
  EXPECT_EQ(r.get<std::uint64_t>("d", 0), 42u);
  EXPECT_EQ(r.get<std::vector<std::size_t>>("e", {}), (std::vector<std::size_t>{28, 20}));
  EXPECT_DOUBLE_EQ(r.get<double>("f", 0), 1e-4);
  EXPECT_EQ(r.section("sec").get<std::int64_t>("x", 0), -3);
  EXPECT_DOUBLE_EQ(r.get<double>("absent", 7.0), 7.0);
  EXPECT_NO_THROW(doc.check_all_consumed());
}

TEST(Config, WrongTypeNamesFileLineColumnKeyAndValue) {
  auto doc = ConfigDocument::parse("trainer:\n  momentum: fast\n", "x.yaml");
  const auto msg = config_error([&] { doc.root().section("trainer").get<double>("momentum", 0); });
  EXPECT_EQ(msg, "x.yaml:2:13: trainer.momentum = fast: expected a number");
}

TEST(Config, QuotedNumberIsAStringNotANumber) {
  auto doc = ConfigDocument::parse("a: '0.5'\n", "x.yaml");
  EXPECT_NE(config_error([&] { doc.root().get<double>("a", 0); }).find("expected a number"),
            std::string::npos);
}

TEST(Config, NonFiniteAndNegativeAndFractionalIntegersRejected) {
  auto doc = ConfigDocument::parse("a: .nan\nb: -1\nc: 2.5\nd: inf\n", "x.yaml");
  auto r = doc.root();
  EXPECT_NE(config_error([&] { r.get<double>("a", 0); }).find("x.yaml:1:4: a = .nan"),
            std::string::npos);
  EXPECT_NE(config_error([&] { r.get<std::uint64_t>("b", 0); }).find("non-negative integer"),
            std::string::npos);
  EXPECT_NE(config_error([&] { r.get<std::int64_t>("c", 0); }).find("expected an integer"),
            std::string::npos);
  EXPECT_NE(config_error([&] { r.get<double>("d", 0); }).find("finite"), std::string::npos);
}

TEST(Config, UnknownKeyIsAnErrorWithSuggestion) {
  auto doc = ConfigDocument::parse("trainer:\n  momentm: 0.5\n  learning_rate: 1\n", "x.yaml");
  auto t = doc.root().section("trainer");
  t.get<double>("momentum", 0.8);
  t.get<double>("learning_rate", 0.1);
  const auto msg = config_error([&] { doc.check_all_consumed(); });
  EXPECT_NE(msg.find("x.yaml:2:12: trainer.momentm: unknown key (did you mean 'momentum'?)"),
            std::string::npos)
      << msg;
}

TEST(Config, UnreadSectionIsUnknown) {
  auto doc = ConfigDocument::parse("trainr:\n  momentum: 0.5\n", "x.yaml");
  doc.root().section("trainer");
  EXPECT_NE(config_error([&] { doc.check_all_consumed(); }).find("trainr: unknown key"),
            std::string::npos);
}

TEST(Config, MalformedYamlNamesPosition) {
  const auto msg = config_error([] { ConfigDocument::parse("a: [1, 2\nb: 3\n", "bad.yaml"); });
  EXPECT_EQ(msg.rfind("bad.yaml:", 0), 0u) << msg;
  EXPECT_NE(msg.find("malformed YAML"), std::string::npos);
}

TEST(Config, DuplicateKeyRejected) {
  EXPECT_NE(config_error([] {
              ConfigDocument::parse("a: 1\na: 2\n", "d.yaml");
            }).find("d.yaml:2:1: a: duplicate key"),
            std::string::npos);
}

TEST(Config, TopLevelMustBeAMap) {
  EXPECT_NE(config_error([] { ConfigDocument::parse("- 1\n- 2\n", "l.yaml"); }).find("map"),
            std::string::npos);
}

TEST(Config, MissingFileIsConfigError) {
  EXPECT_NE(config_error([] { ConfigDocument::load("/nonexistent/x.yaml"); }).find("no such file"),
            std::string::npos);
}

TEST(Config, IncludesMergeLaterOverridesEarlierAndKeepLocations) {
  TempDir dir;
  dir.write("configs/base.yaml", "trainer:\n  momentum: 0.5\n  epochs: 10\nname: base\n");
  const auto exp =
      dir.write("experiments/e.yaml", "include: ../configs/base.yaml\ntrainer:\n  epochs: 20\n");
  auto doc = ConfigDocument::load(exp);
  auto t = doc.root().section("trainer");
  EXPECT_DOUBLE_EQ(t.get<double>("momentum", 0), 0.5);  // from the include
  EXPECT_EQ(t.get<std::uint64_t>("epochs", 0), 20u);    // overridden by the file
  EXPECT_EQ(doc.location("trainer.momentum").file,
            (dir.path() / "experiments/../configs/base.yaml").string());
  EXPECT_EQ(doc.location("trainer.epochs").line, 3);
  EXPECT_EQ(doc.location("trainer.epochs").file, exp.string());
}

TEST(Config, IncludeResolvesAgainstProjectConfigsFolder) {
  TempDir dir;
  dir.write("configs/trainers/sgdm.yaml", "trainer:\n  momentum: 0.25\n");
  const auto exp = dir.write("experiments/deep/e.yaml", "include: [configs/trainers/sgdm.yaml]\n");
  auto doc = ConfigDocument::load(exp);
  EXPECT_DOUBLE_EQ(doc.root().section("trainer").get<double>("momentum", 0), 0.25);
}

// A search with explicit entries: the test's own, not the process's
// environment or current directory.
ConfigSearch search_in(std::vector<fs::path> config_path, fs::path current_dir = {}) {
  ConfigSearch search;
  search.config_path = std::move(config_path);
  search.current_dir = std::move(current_dir);
  return search;
}

double included_momentum(const fs::path& file, const ConfigSearch& search) {
  return ConfigDocument::load(file, "", search)
      .root()
      .section("trainer")
      .get<double>("momentum", -1);
}

TEST(ConfigInclude, SearchOrderIsFileFolderAncestorsConfigPathThenCurrentDirectory) {
  TempDir dir;
  // One candidate per place, each with its own value; removing the one found
  // must reveal the next in the documented order.
  const std::vector<fs::path> places = {
      dir.write("proj/studies/configs/trainers/t.yaml", "trainer: {momentum: 0.1}\n"),
      dir.write("proj/configs/trainers/t.yaml", "trainer: {momentum: 0.2}\n"),
      dir.write("shared1/trainers/t.yaml", "trainer: {momentum: 0.3}\n"),
      dir.write("shared2/trainers/t.yaml", "trainer: {momentum: 0.4}\n"),
      dir.write("work/configs/trainers/t.yaml", "trainer: {momentum: 0.5}\n"),
  };
  const auto exp = dir.write("proj/studies/e.yaml", "include: configs/trainers/t.yaml\n");
  const ConfigSearch search = search_in({dir / "shared1", dir / "shared2"}, dir / "work");
  for (std::size_t i = 0; i < places.size(); ++i) {
    EXPECT_DOUBLE_EQ(included_momentum(exp, search), 0.1 * static_cast<double>(i + 1)) << i;
    fs::remove(places[i]);
  }
  const std::string msg = config_error([&] { ConfigDocument::load(exp, "", search); });
  EXPECT_EQ(
      msg.find(exp.string() + ":1:10: include configs/trainers/t.yaml: not found; looked in: "), 0u)
      << msg;
  // Every place, in order.
  std::size_t at = 0;
  for (const auto& place : places) {
    const std::size_t next = msg.find(place.string(), at);
    EXPECT_NE(next, std::string::npos) << place << " in " << msg;
    if (next != std::string::npos) at = next;
  }
}

TEST(ConfigInclude, AFileOutsideAnyProjectFindsSharedConfigsThroughTheConfigPath) {
  TempDir dir;
  dir.write("cnclab/configs/trainers/t.yaml", "include: configs/base.yaml\ntrainer: {epochs: 3}\n");
  dir.write("cnclab/configs/base.yaml", "trainer: {momentum: 0.7}\n");
  const auto exp = dir.write("home/studies/my.yaml", "include: configs/trainers/t.yaml\n");
  const ConfigSearch search = search_in({dir / "cnclab/configs"});
  const ConfigDocument doc = ConfigDocument::load(exp, "", search);
  // The included file's own configs/ include resolves the same way.
  EXPECT_DOUBLE_EQ(doc.root().section("trainer").get<double>("momentum", -1), 0.7);
  EXPECT_EQ(doc.root().section("trainer").get<std::uint64_t>("epochs", 0), 3u);

  // Without the path: the error says where it looked and how to add a place.
  const std::string msg = config_error([&] { ConfigDocument::load(exp, "", search_in({})); });
  EXPECT_NE(msg.find((dir / "home/studies/configs/trainers/t.yaml").string() +
                     " (relative to the naming file)"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("CNCLAB_CONFIG_PATH"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not set"), std::string::npos) << msg;
}

TEST(ConfigInclude, OnlyConfigsNamesAreSearchedBeyondTheFileFolder) {
  TempDir dir;
  dir.write("shared/trainers/t.yaml", "trainer: {momentum: 0.3}\n");
  dir.write("work/configs/trainers/t.yaml", "trainer: {momentum: 0.5}\n");
  const auto exp = dir.write("a/e.yaml", "include: [trainers/t.yaml]\n");
  const std::string msg = config_error(
      [&] { ConfigDocument::load(exp, "", search_in({dir / "shared"}, dir / "work")); });
  EXPECT_NE(msg.find("include trainers/t.yaml: not found; looked in: " +
                     (dir / "a/trainers/t.yaml").string() + " (relative to the naming file)"),
            std::string::npos)
      << msg;
  EXPECT_EQ(msg.find((dir / "shared").string()), std::string::npos) << msg;
  EXPECT_EQ(msg.find((dir / "work").string()), std::string::npos) << msg;
}

TEST(ConfigInclude, SearchFromEnvironmentSplitsTheConfigPathAndTakesTheCurrentDirectory) {
  const char* old = std::getenv("CNCLAB_CONFIG_PATH");
  const std::optional<std::string> saved = old ? std::optional<std::string>(old) : std::nullopt;
  ::setenv("CNCLAB_CONFIG_PATH", "/a/configs::relative/configs:", 1);
  const ConfigSearch search = ConfigSearch::from_environment();
  EXPECT_EQ(search.config_path,
            (std::vector<fs::path>{"/a/configs", "relative/configs"}));  // empty entries skipped
  EXPECT_EQ(search.current_dir, fs::current_path());
  ::unsetenv("CNCLAB_CONFIG_PATH");
  EXPECT_TRUE(ConfigSearch::from_environment().config_path.empty());
  if (saved) ::setenv("CNCLAB_CONFIG_PATH", saved->c_str(), 1);
}

TEST(Config, IncludeCycleDetected) {
  TempDir dir;
  dir.write("a.yaml", "include: b.yaml\n");
  dir.write("b.yaml", "include: a.yaml\n");
  EXPECT_NE(config_error([&] { ConfigDocument::load(dir.path() / "a.yaml"); }).find("cycle"),
            std::string::npos);
}

TEST(ConfigProfiles, AppliedOnlyWhenNamedAndNeverInTheResolvedTree) {
  const std::string text =
      "trainer:\n  epochs: 2000\n  momentum: 0.8\n"
      "profiles:\n  quick: {trainer.epochs: 20, dataset.samples: 100}\n  other:\n";
  const auto full = ConfigDocument::parse(text, "e.yaml");
  EXPECT_EQ(full.root().section("trainer").get<std::int64_t>("epochs", 0), 2000);
  EXPECT_EQ(full.to_yaml().find("profiles"), std::string::npos);
  full.root().section("trainer").get<double>("momentum", 0);
  full.check_all_consumed();  // `profiles` is gone, not an unread key

  const auto quick = ConfigDocument::parse(text, "e.yaml", "quick");
  EXPECT_EQ(quick.root().section("trainer").get<std::int64_t>("epochs", 0), 20);
  EXPECT_DOUBLE_EQ(quick.root().section("trainer").get<double>("momentum", 0), 0.8);
  EXPECT_EQ(quick.root().section("dataset").get<std::int64_t>("samples", 0),
            100);  // created on the way

  // A profile a file does not define leaves it unchanged.
  EXPECT_EQ(ConfigDocument::parse(text, "e.yaml", "missing").to_yaml(), full.to_yaml());
}

TEST(ConfigProfiles, InheritedThroughIncludesIncludingFileWins) {
  TempDir dir;
  dir.write("base.yaml", "a: 1\nb: 1\nprofiles:\n  quick: {a: 10, b: 10}\n");
  const auto exp = dir.write("e.yaml", "include: base.yaml\nprofiles:\n  quick: {b: 20}\n");
  const auto doc = ConfigDocument::load(exp, "quick");
  EXPECT_EQ(doc.root().get<std::int64_t>("a", 0), 10);
  EXPECT_EQ(doc.root().get<std::int64_t>("b", 0), 20);
}

TEST(ConfigProfiles, CommandLineOverridesComeAfterTheProfile) {
  auto doc = ConfigDocument::parse("a: 1\nprofiles:\n  quick: {a: 2}\n", "e.yaml", "quick");
  doc.apply(parse_override("a=3"));
  EXPECT_EQ(doc.root().get<std::int64_t>("a", 0), 3);
}

TEST(ConfigProfiles, ExclusiveIsASettingNotAnOverride) {
  const std::string text =
      "a: 1\nprofiles:\n  converged: {profile.exclusive: true, a: 2}\n"
      "  quick: {a: 3}\n  off: {profile.exclusive: false}\n";
  const auto doc = ConfigDocument::parse(text, "e.yaml", "converged");
  EXPECT_EQ(doc.root().get<std::int64_t>("a", 0), 2);
  EXPECT_EQ(doc.to_yaml().find("profile"), std::string::npos);  // not written into the tree
  doc.check_all_consumed();
  EXPECT_EQ(doc.profiles(), (std::vector<std::string>{"converged", "quick", "off"}));
  EXPECT_EQ(doc.exclusive_profiles(), std::vector<std::string>{"converged"});
  EXPECT_NE(config_error([] {
              ConfigDocument::parse("profiles:\n  c: {profile.exclusiv: true}\n", "e.yaml");
            }).find("profiles.c.profile.exclusiv: unknown profile setting"),
            std::string::npos);
  EXPECT_NE(config_error([] {
              ConfigDocument::parse("profiles:\n  c: {profile.exclusive: 2}\n", "e.yaml");
            }).find("profiles.c.profile.exclusive: must be true or false, not 2"),
            std::string::npos);
}

TEST(ConfigProfiles, MalformedBlocksAreErrorsNamingTheKey) {
  EXPECT_NE(config_error([] {
              ConfigDocument::parse("profiles: [1, 2]\n", "e.yaml");
            }).find("e.yaml:1:1: profiles: must be a map"),
            std::string::npos);
  EXPECT_NE(config_error([] {
              ConfigDocument::parse("profiles:\n  quick: 3\n", "e.yaml");
            }).find("profiles.quick: must be a map"),
            std::string::npos);
  EXPECT_NE(config_error([] {
              ConfigDocument::parse("profiles:\n  quick: {'a..b': 1}\n", "e.yaml");
            }).find("is not a dotted key"),
            std::string::npos);
  EXPECT_NE(config_error([] {
              ConfigDocument::parse("profiles:\n  quick: {a: ~}\n", "e.yaml", "quick");
            }).find("profiles.quick.a: value is null"),
            std::string::npos);
  // Descending into a scalar names the profile entry and where it is written.
  EXPECT_NE(config_error([] {
              ConfigDocument::parse("a: 1\nprofiles:\n  quick: {a.b: 1}\n", "e.yaml", "quick");
            }).find("profile quick (e.yaml:3:"),
            std::string::npos);
}

TEST(Config, OverrideReplacesValueAndIsNamedInErrors) {
  auto doc = ConfigDocument::parse("trainer:\n  momentum: 0.5\n", "x.yaml");
  doc.apply(parse_override("trainer.momentum=1.5"));
  auto t = doc.root().section("trainer");
  EXPECT_DOUBLE_EQ(t.get<double>("momentum", 0), 1.5);
  EXPECT_EQ(config_error([&] { t.fail("momentum", "must be in [0, 1)"); }),
            "override trainer.momentum=1.5: trainer.momentum = 1.5: must be in [0, 1)");
}

TEST(Config, OverrideCreatesNestedKeysAndListValues) {
  auto doc = ConfigDocument::parse("a: 1\n", "x.yaml");
  doc.apply(parse_override("model.hidden=[28, 20]"));
  EXPECT_EQ(doc.root().section("model").get<std::vector<std::size_t>>("hidden", {}),
            (std::vector<std::size_t>{28, 20}));
}

TEST(Config, OverrideIntoScalarIsAnError) {
  auto doc = ConfigDocument::parse("seed: 1\n", "x.yaml");
  EXPECT_NE(config_error([&] { doc.apply(parse_override("seed.x=2")); }).find("not a section"),
            std::string::npos);
}

TEST(Config, OptionErrorGetsLocation) {
  auto doc = ConfigDocument::parse("trainer:\n  momentum: 1.5\n", "x.yaml");
  auto t = doc.root().section("trainer");
  const auto msg = config_error(
      [&] { t.validate([] { throw OptionError("momentum", "1.5", "must be in [0, 1)"); }); });
  EXPECT_EQ(msg, "x.yaml:2:13: trainer.momentum = 1.5: must be in [0, 1)");
}

TEST(Config, AliasBombIsRejectedNotExpanded) {
  std::string yaml = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i < 9; ++i) {
    // Built by append: "a" + std::to_string(i) trips GCC 12's false
    // -Wrestrict (GCC bug 105329) once inlined.
    const std::string name = std::string("a").append(std::to_string(i));
    const std::string previous = std::string("*a").append(std::to_string(i - 1));
    yaml.append(name).append(": &").append(name).append(" [");
    for (int j = 0; j < 10; ++j) yaml.append(j ? ", " : "").append(previous);
    yaml.append("]\n");
  }
  EXPECT_NE(config_error([&] { ConfigDocument::parse(yaml, "bomb.yaml"); }).find("nodes"),
            std::string::npos);
}

}  // namespace
}  // namespace cnclab

namespace cnclab {
namespace {

// Found by fuzzing: a self-referencing alias is infinitely deep; it must be
// a ConfigError, not a stack overflow.
TEST(Config, RecursiveAliasIsRejected) {
  EXPECT_NE(
      config_error([] { ConfigDocument::parse("a: &a [*a]\n", "r.yaml"); }).find("nested deeper"),
      std::string::npos);
}

}  // namespace
}  // namespace cnclab
