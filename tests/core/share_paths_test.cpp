#include "cnclab/core/share_paths.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {
namespace fs = std::filesystem;

fs::path write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
  return path;
}

// The compiled-in install folder (CMAKE_INSTALL_PREFIX/share/cnclab) is
// searched too; these tests assume it holds no cnclab, as on a build machine.
bool compiled_in_share_absent() {
  return share_roots_for("").roots.empty();
}

TEST(ShareRoots, AnInstalledExecutableFindsTheShareFolderBesideItsBinFolder) {
  testing::TempDir dir;
  const fs::path exe = write_file(dir / "prefix/bin/cnclab", "");
  const ShareRoots absent = share_roots_for(exe);
  if (!compiled_in_share_absent()) GTEST_SKIP() << "cnclab installed at the compiled-in prefix";
  EXPECT_TRUE(absent.roots.empty());
  ASSERT_FALSE(absent.absent.empty());
  EXPECT_NE(absent.absent.front().find((dir / "prefix/share/cnclab").string() + ": absent"),
            std::string::npos)
      << absent.absent.front();
  EXPECT_NE(absent.none_note().find("no cnclab share folder ("), std::string::npos);

  fs::create_directories(dir / "prefix/share/cnclab");
  const ShareRoots found = share_roots_for(exe);
  ASSERT_EQ(found.roots.size(), 1u);
  EXPECT_EQ(fs::canonical(found.roots[0].dir), fs::canonical(dir / "prefix/share/cnclab"));
  EXPECT_EQ(found.roots[0].why, "installed, next to the executable");
}

TEST(ShareRoots, AnExecutableInTheBuildTreeFallsBackToTheSourceTree) {
  const ShareRoots roots = share_roots_for(CNCLAB_BINARY_DIR "/cnclab");
  ASSERT_FALSE(roots.roots.empty());
  EXPECT_EQ(fs::canonical(roots.roots.back().dir), fs::canonical(CNCLAB_SOURCE_DIR));
  EXPECT_EQ(roots.roots.back().why, "source tree of this build");
  // This test binary lies in the build tree too.
  const ShareRoots self = installed_share_roots();
  ASSERT_FALSE(self.roots.empty());
  EXPECT_EQ(fs::canonical(self.roots.back().dir), fs::canonical(CNCLAB_SOURCE_DIR));
}

TEST(FindShared, TheProjectComesFirstThenEachRootInOrder) {
  testing::TempDir dir;
  const fs::path name = "results/reference/t.yaml";
  write_file(dir / "a" / name, "a");
  write_file(dir / "b" / name, "b");
  const ShareRoots roots{{{dir / "a", "first"}, {dir / "b", "second"}}, {}};
  // Not in the project (the current directory holds no results/reference/t.yaml).
  ShareLookup lookup = find_shared(name, true, roots);
  ASSERT_TRUE(lookup.found);
  EXPECT_EQ(*lookup.found, dir / "a" / name);
  ASSERT_EQ(lookup.tried.size(), 2u);
  EXPECT_EQ(lookup.tried[0].first, name);  // the project: as given, relative
  EXPECT_EQ(lookup.tried[0].second, "the project: current directory");

  fs::remove(dir / "a" / name);
  lookup = find_shared(name, false, roots);
  ASSERT_TRUE(lookup.found);
  EXPECT_EQ(*lookup.found, dir / "b" / name);
  EXPECT_EQ(lookup.tried.size(), 2u);  // a, then b: no project

  fs::remove(dir / "b" / name);
  lookup = find_shared(name, true, roots);
  EXPECT_FALSE(lookup.found);
  EXPECT_EQ(lookup.not_found_message(name),
            name.string() + " not found; looked in: " + name.string() +
                " (the project: current directory), " + (dir / "a" / name).string() + " (first), " +
                (dir / "b" / name).string() + " (second)");
}

TEST(FindShared, WithoutAnyShareFolderTheMessageSaysWhichWereAbsent) {
  const ShareRoots none{{}, {"installed, next to the executable /x/share/cnclab: absent"}};
  const ShareLookup lookup = find_shared("configs/none.yaml", false, none);
  EXPECT_FALSE(lookup.found);
  EXPECT_EQ(lookup.not_found_message("configs/none.yaml"),
            "configs/none.yaml not found; no cnclab share folder (installed, next to "
            "the executable /x/share/cnclab: absent)");
}

TEST(FindShared, RequireSharedListsEveryPlaceInItsError) {
  try {
    require_shared("results/reference/no_such_paper.yaml");
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("results/reference/no_such_paper.yaml (the project: current directory)"),
              std::string::npos)
        << msg;
    // The test binary's share root: the source tree.
    EXPECT_NE(msg.find(std::string(CNCLAB_SOURCE_DIR) +
                       "/results/reference/no_such_paper.yaml (source tree of this build)"),
              std::string::npos)
        << msg;
  }
}

// Includes: the project's configs/ (ancestors, CNCLAB_CONFIG_PATH, the
// current directory's) come before cnclab's own configs of each share root.
TEST(ConfigIncludeShared, ShareRootsAreSearchedAfterTheCurrentDirectory) {
  testing::TempDir dir;
  const fs::path installed =
      write_file(dir / "share/configs/trainers/t.yaml", "trainer: {momentum: 0.3}\n");
  const fs::path own =
      write_file(dir / "work/configs/trainers/t.yaml", "trainer: {momentum: 0.5}\n");
  const fs::path exp = write_file(dir / "home/e.yaml", "include: configs/trainers/t.yaml\n");
  ConfigSearch search;
  search.current_dir = dir / "work";
  search.shared = ShareRoots{{{dir / "share", "installed, next to the executable"}}, {}};
  const auto momentum = [&] {
    return ConfigDocument::load(exp, "", search)
        .root()
        .section("trainer")
        .get<double>("momentum", -1);
  };
  EXPECT_DOUBLE_EQ(momentum(), 0.5);  // the project's own
  fs::remove(own);
  EXPECT_DOUBLE_EQ(momentum(), 0.3);  // the installed one
  fs::remove(installed);
  try {
    ConfigDocument::load(exp, "", search);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find((dir / "work/configs/trainers/t.yaml").string() +
                       " (configs/ of the current directory), " + installed.string() +
                       " (cnclab's configs, installed, next to the executable)"),
              std::string::npos)
        << msg;
  }
}

}  // namespace
}  // namespace cnclab
