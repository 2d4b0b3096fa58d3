// Core tests build their graphs from graph text: the YAML a user writes (docs/graph_format.md).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "apex/core/graph.hpp"
#include "apex/core/graph_file.hpp"

namespace apex_test {

/** Replaces the graph in `g` with the graph of `yaml`: a graph file, which may leave out the line
 *  `apex_graph: 2` and may be indented as a whole (as in a raw string in a test). Fails with the
 *  parser's or the load's message, or with a load warning (a mistyped type would otherwise load as
 *  a placeholder). Use as ASSERT_TRUE(buildFromText(g, R"(...)")). */
[[nodiscard]] inline ::testing::AssertionResult buildFromText(apex::Graph& g, const std::string& yaml) {
  std::vector<std::string> lines;
  std::size_t indent = std::string::npos;  // of the least indented line that is not blank
  std::istringstream in(yaml);
  for (std::string line; std::getline(in, line);) {
    const auto first = line.find_first_not_of(' ');
    if (first != std::string::npos) indent = std::min(indent, first);
    lines.push_back(line);
  }
  std::string text = yaml.find("apex_graph:") == std::string::npos ? "apex_graph: 2\n" : "";
  for (const auto& line : lines) text += line.substr(std::min(indent, line.size())) + "\n";
  auto parsed = apex::parseGraphText(text);
  if (!parsed) return ::testing::AssertionFailure() << parsed.message() << " in\n" << text;
  auto loaded = g.load(parsed.value());
  if (!loaded) return ::testing::AssertionFailure() << loaded.message() << " in\n" << text;
  if (!loaded->warnings.empty()) return ::testing::AssertionFailure() << loaded->warnings.front() << " in\n" << text;
  return ::testing::AssertionSuccess();
}

}  // namespace apex_test
