// Helpers shared by the graph file tests: substring checks, a temporary
// directory, whole-file reads and writes, and a graph using every feature.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "apex/core/graph.hpp"
#include "apex_test/test_nodes.hpp"

namespace apex_test {

namespace fs = std::filesystem;

inline ::testing::AssertionResult Contains(const std::string& text, const std::vector<std::string>& parts) {
  for (const auto& p : parts)
    if (text.find(p) == std::string::npos)
      return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << p << "'";
  return ::testing::AssertionSuccess();
}

/** A fresh directory (mkdtemp), removed with everything in it at the end of the test. */
struct TempDir {
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "apex_graph_file_XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
    path = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
  /** Every entry's file name, sorted. */
  std::vector<std::string> entries() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(path)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }
  fs::path path;
};

inline std::string readFile(const std::string& path) {
  std::stringstream s;
  s << std::ifstream(path).rdbuf();
  return s.str();
}
inline void writeFile(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

/** A graph using every feature the file records. */
inline void buildRichGraph(Graph& g) {
  add(g, "test/Feeder", "feeder"), add(g, "test/Gain", "g1", "vision"), add(g, "test/Gain", "g2");
  add(g, "test/Collector", "sink"), add(g, "test/Counter", "c1", "vision"), add(g, "test/Counter", "c2");
  link(g, "feeder", "out", "g1", "in"), link(g, "g1", "out", "g2", "in");
  link(g, "g2", "out", "sink", "in"), link(g, "feeder", "out", "c1", "in");
  ASSERT_TRUE(g.setParameter("g1", "gain", "7"));
  ASSERT_TRUE(g.setParameter("c1", "every", "2"));
  ASSERT_TRUE(g.setInteractive("g1", "gain", true));
  ASSERT_TRUE(g.setInteractive("g2", "gain", true));
  link(g, "g1", "gain", "g2", "gain");
  link(g, "c1", "every_n", "c2", "reset");
  ASSERT_TRUE(g.setEnabled("c2", false));
  ASSERT_TRUE(g.setUi("g1", "{x: 10, y: 20}"));
  ASSERT_TRUE(g.setUi("sink", "{x: 300, y: 20, collapsed: true}"));
}

}  // namespace apex_test
