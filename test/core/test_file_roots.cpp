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
  // a labelling tool's truth: one file, or a folder of one file per image
  EXPECT_TRUE(roots.check(root + "/graphs/g.yaml", PathMode::ReadFileOrFolder));
  EXPECT_TRUE(roots.check(root + "/graphs", PathMode::ReadFileOrFolder));
  EXPECT_TRUE(Contains(roots.check(root + "/labels", PathMode::ReadFileOrFolder).message(), {"no such file or folder"}));
  EXPECT_TRUE(Contains(roots.check(root + "/pipe", PathMode::ReadFileOrFolder).message(), {"not a file or a folder"}));
  EXPECT_TRUE(Contains(roots.check("/etc", PathMode::ReadFileOrFolder).message(), {"outside"}));
}

TEST_F(Roots, ARelativePathIsTakenInsideTheFirstWritableRoot) {
  const std::string second = dir.file("second");
  fs::create_directories(second);
  FileRoots two({second, root});
  EXPECT_EQ(two.resolve("tuned.yaml", FileRoots::Access::Write).value(), fs::weakly_canonical(second).string() + "/tuned.yaml");
  EXPECT_EQ(two.resolve("../root/graphs/g.yaml").value(), roots.resolve(root + "/graphs/g.yaml").value());
  EXPECT_FALSE(two.resolve("../elsewhere/x.yaml")) << "relative, and still confined";
}

TEST_F(Roots, AReadOnlyRootIsReadAndNeverWrittenEvenInsideAWritableOne) {
  const std::string shipped = root + "/graphs";  // a package's shipped graphs, inside a writable root
  roots.readOnly({shipped});
  EXPECT_TRUE(roots.check(shipped + "/g.yaml", PathMode::Read));
  auto save = roots.resolve(shipped + "/g.yaml", FileRoots::Access::Write);
  ASSERT_FALSE(save);
  const std::string canonical = fs::weakly_canonical(root).string();
  EXPECT_TRUE(
      Contains(save.message(), {"path '" + shipped + "/g.yaml'",
                                "lies in '" + canonical + "/graphs', whose files may be read, not written: write it in " +
                                    canonical + " (a path without a folder, such as 'g.yaml', goes to " + canonical + ")"}))
      << save.message();
  EXPECT_FALSE(roots.check(shipped + "/new", PathMode::Directory)) << "a node's export folder writes too";
  EXPECT_TRUE(roots.check(root + "/new.yaml", PathMode::Write));
  EXPECT_EQ(roots.list(), canonical + "; read only: " + canonical + "/graphs");

  FileRoots only_read = FileRoots().readOnly({shipped});
  EXPECT_TRUE(only_read.resolve(shipped + "/g.yaml"));
  EXPECT_TRUE(
      Contains(only_read.resolve(dir.file("x.yaml")).message(), {"outside the folders files may be read from (read only: "}));
  EXPECT_TRUE(Contains(only_read.resolve(dir.file("x.yaml"), FileRoots::Access::Write).message(),
                       {"outside the folders files may be written in (none)"}));
}

TEST_F(Roots, DotsAfterAFolderThatDoesNotExistCannotHideALinkOutOfTheRoot) {
  ASSERT_EQ(::symlink("/etc", (root + "/etc_link").c_str()), 0);
  // on paper missing/.. cancels out and etc_link/passwd is inside; the system follows the link
  auto r = roots.resolve(root + "/missing/../etc_link/passwd");
  ASSERT_FALSE(r);
  EXPECT_TRUE(Contains(r.message(), {"'..' after a folder that does not exist"}));
  EXPECT_TRUE(roots.resolve(root + "/graphs/../graphs/g.yaml")) << "'..' after a folder that is there: fine";
}

TEST_F(Roots, AWritableRootInsideAReadOnlyOneIsReadOnly) {
  FileRoots nested({root + "/graphs", dir.file("other")});  // the first would take relative paths
  nested.readOnly({root});
  EXPECT_EQ(nested.roots(), std::vector<std::string>{fs::weakly_canonical(dir.file("other")).string()});
  EXPECT_TRUE(nested.resolve(root + "/graphs/g.yaml"));
  EXPECT_FALSE(nested.resolve(root + "/graphs/g.yaml", FileRoots::Access::Write));
  EXPECT_EQ(nested.resolve("new.yaml", FileRoots::Access::Write).value(),
            fs::weakly_canonical(dir.file("other")).string() + "/new.yaml");
}

TEST_F(Roots, TrustedPathsAreTakenFromTheCurrentFolder) {
  // what the operator's launch names (the start-up graph, ~overrides): a relative path is the
  // process's, as the shell that gave it meant; only service paths go to the first root
  EXPECT_EQ(FileRoots::anywhere({}).resolve("graphs/demo.yaml").value(),
            fs::weakly_canonical(fs::absolute("graphs/demo.yaml")).string());
  EXPECT_EQ(roots.resolve("g.yaml").value(), fs::weakly_canonical(root).string() + "/g.yaml");
}

TEST_F(Roots, ARefusalSaysHowToAllowTheFolder) {
  roots.hint([](const std::string& folder) { return "; add '" + folder + "' to ~file_roots"; });
  EXPECT_TRUE(Contains(roots.resolve("/etc/apex_probe.yaml", FileRoots::Access::Write).message(),
                       {"written in (" + fs::weakly_canonical(root).string() + "); add '/etc' to ~file_roots"}));
  EXPECT_TRUE(Contains(roots.check("/var/tmp", PathMode::Directory).message(), {"add '/var/tmp' to"})) << "a folder itself";
}

}  // namespace
