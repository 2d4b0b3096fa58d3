// Paths from outside are confined to the roots: resolved first (package://, $(find),
// ~, .., symlinks), then refused with the path and the roots named if outside.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>

#include "apex/core/file_roots.hpp"
#include "apex_test/graph_file_helpers.hpp"

using namespace apex_test;
using apex::FileRoots;
using apex::PathMode;

namespace {

struct Roots : ::testing::Test {
  TempDir dir;
  std::string root = dir.file("root");
  FileRoots roots;
  void SetUp() override {
    fs::create_directories(root + "/graphs");
    writeFile(root + "/graphs/g.yaml", "apex_graph: 1\n");
    roots = FileRoots({root}, [this](const std::string& pkg) { return pkg == "demo" ? root : std::string(); });
  }
};

TEST_F(Roots, APathInsideIsResolved) {
  EXPECT_EQ(roots.resolve(root + "/graphs/g.yaml").value(), fs::weakly_canonical(root + "/graphs/g.yaml").string());
  EXPECT_EQ(roots.resolve(root + "/graphs/new.yaml").value(), fs::weakly_canonical(root).string() + "/graphs/new.yaml");
  EXPECT_EQ(roots.resolve("package://demo/graphs/g.yaml").value(), roots.resolve(root + "/graphs/g.yaml").value());
  EXPECT_EQ(roots.resolve("$(find demo)/graphs/g.yaml").value(), roots.resolve(root + "/graphs/g.yaml").value());
}

TEST_F(Roots, APathOutsideIsRefusedNamingPathAndRoots) {
  auto r = roots.resolve("/etc/apex_probe.yaml");
  ASSERT_FALSE(r);
  EXPECT_TRUE(Contains(r.message(), {"'/etc/apex_probe.yaml'", "outside", roots.list(), "~file_roots"}));
  EXPECT_FALSE(roots.resolve(root + "/graphs/../../../etc/x.yaml")) << "escaped by ..";
  EXPECT_FALSE(roots.resolve(root + "_other/x.yaml")) << "a sibling whose name starts like the root";
  EXPECT_FALSE(roots.resolve("relative/../../x.yaml"));
  EXPECT_FALSE(roots.resolve("package://unknown/x.yaml"));
  EXPECT_TRUE(Contains(roots.resolve("package://unknown/x.yaml").message(), {"unknown package 'unknown'"}));
  EXPECT_FALSE(FileRoots().resolve(root + "/graphs/g.yaml")) << "no roots: nothing is allowed";
}

TEST_F(Roots, ASymlinkOutOfTheRootIsRefused) {
  ASSERT_EQ(::symlink("/etc", (root + "/etc_link").c_str()), 0);
  auto r = roots.resolve(root + "/etc_link/passwd");
  ASSERT_FALSE(r);
  EXPECT_TRUE(Contains(r.message(), {"'/etc/passwd'"}));
}

TEST_F(Roots, HomeIsExpanded) {
  const char* old = std::getenv("HOME");
  const std::string saved = old ? old : "";
  ::setenv("HOME", root.c_str(), 1);
  EXPECT_EQ(roots.resolve("~/graphs/g.yaml").value(), roots.resolve(root + "/graphs/g.yaml").value());
  ::setenv("HOME", saved.c_str(), 1);
}

TEST_F(Roots, EachModeChecksWhatItNeeds) {
  EXPECT_TRUE(roots.check(root + "/graphs/g.yaml", PathMode::Read));
  EXPECT_TRUE(Contains(roots.check(root + "/graphs/none.yaml", PathMode::Read).message(), {"no such file"}));
  ASSERT_EQ(::mkfifo((root + "/pipe").c_str(), 0644), 0);
  EXPECT_TRUE(Contains(roots.check(root + "/pipe", PathMode::Read).message(), {"not a regular file"}));
  EXPECT_TRUE(Contains(roots.check(root + "/pipe", PathMode::Write).message(), {"not a regular file"}));
  EXPECT_TRUE(roots.check(root + "/graphs/new.yaml", PathMode::Write));
  EXPECT_TRUE(Contains(roots.check(root + "/missing/new.yaml", PathMode::Write).message(), {"does not exist"}));
  EXPECT_TRUE(roots.check(root + "/graphs", PathMode::Directory));
  EXPECT_TRUE(roots.check(root + "/export", PathMode::Directory)) << "a folder a node will make";
  EXPECT_TRUE(Contains(roots.check(root + "/graphs/g.yaml", PathMode::Directory).message(), {"not a folder"}));
}

}  // namespace
