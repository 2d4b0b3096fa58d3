// docs/nodes.md and the manifests it is made from: every type of APEX's own libraries has a
// description and one of the categories, and the file in the repository is what the manifests give
// now (scripts/node_docs writes it).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "../../apex_nodes/tools/node_docs.hpp"
#include "apex_test/node_harness.hpp"

namespace {

/** docs/nodes.md of the source tree this test was built from (APEX_SOURCE_DIR, from CMake: __FILE__
 *  is relative when ccache compiles it, its paths hashed relative to a folder above). */
std::string docsPath() { return std::string(APEX_SOURCE_DIR) + "/docs/nodes.md"; }

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

TEST(NodeDocs, EveryOwnTypeHasADescriptionAndACategory) {
  const auto& known = apex_node_docs::categories();
  std::size_t own = 0;
  for (const auto& type : apex_test::pluginRegistry().types()) {
    if (!apex_node_docs::isOwn(type->id)) continue;
    ++own;
    const apex::Manifest& m = *type->manifest;
    EXPECT_FALSE(m.description.empty()) << type->id << " has no description: give its Manifest one";
    EXPECT_TRUE(std::find(known.begin(), known.end(), m.category) != known.end())
        << type->id << " has the category '" << m.category
        << "': call .inCategory(...) in its manifest() with one of apex::nodeCategories() (apex/core/categories.hpp)";
  }
  EXPECT_GT(own, 0u) << "no apex_nodes/ types loaded: is the devel space sourced?";
}

TEST(NodeDocs, TheFileIsUpToDate) {
  const std::string path = docsPath();
  ASSERT_EQ(path.rfind('/', 0), 0u) << "APEX_SOURCE_DIR is not an absolute path (" << path << ")";
  std::ifstream file(path, std::ios::binary);
  ASSERT_TRUE(file) << "docs/nodes.md is stale: run scripts/node_docs (cannot read " << path << ")";
  std::ostringstream read;
  read << file.rdbuf();
  const std::string expected = apex_node_docs::nodeDocs(apex_test::pluginRegistry());
  const std::string actual = read.str();
  if (actual == expected) return;
  const auto want = lines(expected), have = lines(actual);
  std::size_t i = 0;
  while (i < want.size() && i < have.size() && want[i] == have[i]) ++i;
  if (i == want.size() && i == have.size()) {  // the same lines: the newline at the end differs
    ADD_FAILURE() << "docs/nodes.md is stale: run scripts/node_docs\n(the same lines, but not the same newline at the end)";
    return;
  }
  const std::string generated = i < want.size() ? "'" + want[i] + "'" : "(end of file)";
  const std::string in_file = i < have.size() ? "'" + have[i] + "'" : "(end of file)";
  ADD_FAILURE() << "docs/nodes.md is stale: run scripts/node_docs\n"
                << "first difference at line " << i + 1 << ":\n  the manifests give: " << generated
                << "\n  docs/nodes.md has:   " << in_file;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
