// Shared by the subgraph tests (test_subgraph.cpp, test_subgraph_edits.cpp): a subgraph file,
// a graph using it twice, and running a graph fed 1..n.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "apex/core/graph.hpp"
#include "apex/core/graph_file.hpp"
#include "apex_test/graph_file_helpers.hpp"
#include "apex_test/test_nodes.hpp"

namespace apex_test {
namespace subgraphs {

// in × a × b, as a file other graphs use
inline const char* kScale =
    "apex_graph: 2\n"
    "exports:\n"
    "  - {input: in, to: first/in}\n"
    "  - {output: out, from: second/out}\n"
    "  - {parameter: factor, to: second/gain, description: the second factor}\n"
    "nodes:\n"
    "  - {name: first, type: test/Gain, parameters: {gain: 3}}\n"
    "  - {name: second, type: test/Gain, parameters: {gain: 2}}\n"
    "connections:\n"
    "  - {from: first/out, to: second/in}\n";

inline std::string twoInstances(const std::string& ref) {
  return "apex_graph: 2\n"
         "nodes:\n"
         "  - {name: feeder, type: test/Feeder}\n"
         "  - {name: a, subgraph: " +
         ref +
         ", parameters: {factor: 5}}\n"
         "  - {name: b, subgraph: " +
         ref +
         "}\n"
         "  - {name: sink_a, type: test/Collector}\n"
         "  - {name: sink_b, type: test/Collector}\n"
         "connections:\n"
         "  - {from: feeder/out, to: a/in}\n"
         "  - {from: feeder/out, to: b/in}\n"
         "  - {from: a/out, to: sink_a/in}\n"
         "  - {from: b/out, to: sink_b/in}\n";
}

/** Feeds 1..n and returns what `sink` got. */
inline std::vector<int> run(apex::Graph& g, const std::string& sink, int n = 4) {
  g.start();
  for (int i = 1; i <= n; ++i) object<Feeder>(g, "feeder")->feed(i);
  EXPECT_TRUE(object<Collector>(g, sink)->waitFor(n));
  EXPECT_TRUE(g.waitIdle(apex_test::kWait));
  g.stop();
  return object<Collector>(g, sink)->ints();
}

inline apex::Result<apex::LoadReport> loadText(apex::Graph& g, TempDir& dir, const std::string& name, const std::string& text) {
  writeFile(dir.file(name), text);
  return apex::loadGraphFile(g, dir.file(name));
}

/** scale.yaml (kScale) and main.yaml using it twice (twoInstances) in `dir`, main.yaml loaded into `g`. */
inline apex::Result<apex::LoadReport> loadTwoScales(apex::Graph& g, TempDir& dir) {
  writeFile(dir.file("scale.yaml"), kScale);
  return loadText(g, dir, "main.yaml", twoInstances("scale.yaml"));
}

}  // namespace subgraphs
}  // namespace apex_test
