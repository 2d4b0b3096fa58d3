// Subgraphs: a group of nodes used as one node through the ports, parameters and
// events it exports; inline or from a file; flattened, so they run like any node.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "apex/core/file_roots.hpp"
#include "apex_test/subgraph_helpers.hpp"

namespace {

using namespace apex;
using namespace apex_test;
using namespace apex_test::subgraphs;

TEST(Subgraph, InlineSubgraphRunsLikeTheFlatChain) {
  const std::string nested =
      "apex_graph: 2\n"
      "nodes:\n"
      "  - name: feeder\n    type: test/Feeder\n"
      "  - name: scale\n    subgraph:\n"
      "      exports:\n"
      "        - {input: in, to: first/in}\n"
      "        - {output: out, from: second/out}\n"
      "      nodes:\n"
      "        - {name: first, type: test/Gain, parameters: {gain: 3}}\n"
      "        - {name: second, type: test/Gain, parameters: {gain: 2}}\n"
      "      connections:\n"
      "        - {from: first/out, to: second/in}\n"
      "  - name: sink\n    type: test/Collector\n"
      "connections:\n"
      "  - {from: feeder/out, to: scale/in}\n"
      "  - {from: scale/out, to: sink/in}\n";
  const std::string flat =
      "apex_graph: 1\n"
      "nodes:\n"
      "  - {name: feeder, type: test/Feeder}\n"
      "  - {name: first, type: test/Gain, parameters: {gain: 3}}\n"
      "  - {name: second, type: test/Gain, parameters: {gain: 2}}\n"
      "  - {name: sink, type: test/Collector}\n"
      "connections:\n"
      "  - {from: feeder/out, to: first/in}\n"
      "  - {from: first/out, to: second/in}\n"
      "  - {from: second/out, to: sink/in}\n";
  Graph grouped(testRegistry()), plain(testRegistry());
  auto parsed = parseGraphText(nested);
  ASSERT_TRUE(parsed) << parsed.message();
  auto loaded = grouped.load(parsed.value());
  ASSERT_TRUE(loaded) << loaded.message();
  ASSERT_TRUE(plain.load(parseGraphText(flat).value()));
  EXPECT_EQ(grouped.size(), 4u);  // the inner nodes are nodes of the graph: no node of its own
  EXPECT_EQ(run(grouped, "sink"), run(plain, "sink"));
  EXPECT_EQ(run(plain, "sink"), (std::vector<int>{6, 12, 18, 24, 6, 12, 18, 24}));

  const std::string text = formatGraphText(grouped.describe());
  EXPECT_TRUE(Contains(text, {"apex_graph: 2", "subgraph:", "{input: in, to: first/in}", "{from: scale/out, to: sink/in}",
                              "{from: first/out, to: second/in}"}))
      << text;
  Graph again(testRegistry());
  ASSERT_TRUE(again.load(parseGraphText(text).value()));
  EXPECT_EQ(formatGraphText(again.describe()), text);
}

TEST(Subgraph, InnerNodesAreAddressedByPathByEveryEdit) {
  TempDir dir;
  Graph g(testRegistry());
  auto loaded = loadTwoScales(g, dir);
  ASSERT_TRUE(loaded) << loaded.message();

  // the exported parameter and the inner one are the same value
  EXPECT_EQ(std::get<int>(g.parameterValue("a", "factor").value()), 5);
  EXPECT_EQ(std::get<int>(g.parameterValue("a/second", "gain").value()), 5);
  ASSERT_TRUE(g.setParameter("a/first", "gain", "4"));
  ASSERT_TRUE(g.setParameter("a", "factor", "1"));
  EXPECT_EQ(std::get<int>(g.parameterValue("a/second", "gain").value()), 1);
  auto iface = g.nodeInterface("a");
  ASSERT_TRUE(iface);
  ASSERT_TRUE(iface->findParam("factor"));
  EXPECT_EQ(iface->findParam("factor")->description, "the second factor");
  EXPECT_EQ(std::get<int>(iface->findParam("factor")->default_value), 2);  // what the file gives
  EXPECT_TRUE(iface->findInput("in") && iface->findOutput("out"));

  std::vector<std::string> names;
  for (const auto& s : g.nodeStats()) names.push_back(s.name);
  EXPECT_TRUE(std::find(names.begin(), names.end(), "b/second") != names.end());

  // connect and disconnect inside, and across the boundary by an inner name
  ASSERT_TRUE(g.disconnect("a", "out", "sink_a", "in"));
  ASSERT_TRUE(g.connect("a/first", "out", "sink_a", "in"));
  EXPECT_EQ(run(g, "sink_a", 2), (std::vector<int>{4, 8}));
  // a node added inside a subgraph is part of it
  auto added = g.addNode("test/Relay", "a/extra");
  ASSERT_TRUE(added) << added.message();
  EXPECT_TRUE(findNode(g.describe(), "a/extra"));
  auto nowhere = g.addNode("test/Relay", "nope/extra");
  EXPECT_TRUE(Contains(nowhere.message(), {"no subgraph 'nope'"})) << nowhere.message();
  auto wrong = g.connect("feeder", "out", "a", "image");
  EXPECT_TRUE(Contains(wrong.message(), {"subgraph 'a' exports no input, slot or parameter 'image'", "in (input)"}))
      << wrong.message();
  auto no_param = g.setParameter("a", "gain", "2");
  EXPECT_TRUE(Contains(no_param.message(), {"exports no parameter 'gain'", "factor"})) << no_param.message();
}

TEST(Subgraph, TwoInstancesOfOneFileKeepTheirOwnParameters) {
  TempDir dir;
  Graph g(testRegistry());
  auto loaded = loadTwoScales(g, dir);
  ASSERT_TRUE(loaded) << loaded.message();
  g.start();
  for (int i = 1; i <= 3; ++i) object<Feeder>(g, "feeder")->feed(i);
  ASSERT_TRUE(object<Collector>(g, "sink_a")->waitFor(3));
  ASSERT_TRUE(object<Collector>(g, "sink_b")->waitFor(3));
  g.stop();
  EXPECT_EQ(object<Collector>(g, "sink_a")->ints(), (std::vector<int>{15, 30, 45}));
  EXPECT_EQ(object<Collector>(g, "sink_b")->ints(), (std::vector<int>{6, 12, 18}));

  // saved as references with their own values, and read back the same
  const std::string text = formatGraphText(g.describe());
  EXPECT_TRUE(Contains(text, {"subgraph: scale.yaml", "factor: 5", "factor: 2", "{from: feeder/out, to: a/in}"})) << text;
  EXPECT_EQ(text.find("first/out"), std::string::npos) << text;  // nothing of the inner graph
  ASSERT_TRUE(saveGraphFile(g, dir.file("saved.yaml")));
  Graph again(testRegistry());
  ASSERT_TRUE(loadGraphFile(again, dir.file("saved.yaml")));
  EXPECT_EQ(formatGraphText(again.describe()), text);
}

TEST(Subgraph, ExportedSlotsAndTriggersCarryEventsAcrossTheBoundary) {
  TempDir dir;
  writeFile(dir.file("counted.yaml"),
            "apex_graph: 2\n"
            "exports:\n"
            "  - {input: in, to: count/in}\n"
            "  - {slot: reset, to: count/reset}\n"
            "  - {trigger: every_two, from: count/every_n}\n"
            "nodes:\n"
            "  - {name: count, type: test/Counter, parameters: {every: 2}}\n");
  Graph g(testRegistry());
  auto loaded = loadText(g, dir, "main.yaml",
                         "apex_graph: 2\n"
                         "nodes:\n"
                         "  - {name: feeder, type: test/Feeder}\n"
                         "  - {name: part, subgraph: counted.yaml}\n"
                         "  - {name: watch, type: test/Counter}\n"
                         "connections:\n"
                         "  - {from: feeder/out, to: part/in}\n"
                         "  - {from: part/every_two, to: watch/reset}\n");
  ASSERT_TRUE(loaded) << loaded.message();
  g.start();
  for (int i = 1; i <= 4; ++i) object<Feeder>(g, "feeder")->feed(i);
  auto* inner = object<apex_test::Counter>(g, "part/count");
  auto* watch = object<apex_test::Counter>(g, "watch");
  ASSERT_TRUE(inner && watch);
  // the inner trigger, exported, reaches a slot outside: every second input
  ASSERT_TRUE(apex_test::waitUntil([&] { return watch->resets == 2; }));
  // the exported slot reaches the inner node's slot
  ASSERT_TRUE(g.fireSlot("part", "reset"));
  ASSERT_TRUE(apex_test::waitUntil([&] { return inner->resets == 1; }));
  EXPECT_EQ(inner->count, 0);
  auto wrong = g.fireSlot("part", "restart");
  EXPECT_FALSE(wrong);
  EXPECT_TRUE(Contains(wrong.message(), {"restart"})) << wrong.message();
  g.stop();
}

TEST(Subgraph, APackageReferenceIsOpenedThroughTheHostsRootsAndKeptAsWritten) {
  TempDir dir;  // the package "demo" is this folder; its graphs/ holds the part
  std::filesystem::create_directories(dir.file("graphs"));
  writeFile(dir.file("graphs/scale.yaml"), kScale);
  const std::string package = dir.path.string();
  const FileRoots roots({package}, [&](const std::string& pkg) { return pkg == "demo" ? package : ""; });
  GraphFileOptions options;  // as the ROS host opens subgraph files of graphs from its services
  options.open = [&](const std::string& path) { return roots.resolve(path); };
  writeFile(dir.file("main.yaml"), twoInstances("package://demo/graphs/scale.yaml"));
  Graph g(testRegistry());
  auto loaded = loadGraphFile(g, dir.file("main.yaml"), options);
  ASSERT_TRUE(loaded) << loaded.message();
  EXPECT_EQ(run(g, "sink_b", 2), (std::vector<int>{6, 12}));
  EXPECT_TRUE(Contains(formatGraphText(g.describe()), {"subgraph: package://demo/graphs/scale.yaml"}));

  writeFile(dir.file("other.yaml"), twoInstances("package://nowhere/graphs/scale.yaml"));
  Graph none(testRegistry());
  auto refused = loadGraphFile(none, dir.file("other.yaml"), options);
  ASSERT_FALSE(refused);
  EXPECT_TRUE(Contains(refused.message(), {"other.yaml", "unknown package 'nowhere'"})) << refused.message();
  EXPECT_EQ(none.size(), 0u);
}

TEST(Subgraph, AnEditInsideAFileBackedSubgraphIsSavedInline) {
  TempDir dir;
  Graph g(testRegistry());
  ASSERT_TRUE(loadTwoScales(g, dir));
  ASSERT_TRUE(g.setParameter("b/first", "gain", "7"));  // not exported: the file no longer says it
  const std::string text = formatGraphText(g.describe());
  EXPECT_TRUE(Contains(text, {"subgraph: scale.yaml", "gain: 7", "{input: in, to: first/in}"})) << text;
  Graph again(testRegistry());
  auto loaded = loadText(again, dir, "edited.yaml", text);
  ASSERT_TRUE(loaded) << loaded.message();
  EXPECT_EQ(run(again, "sink_b", 1), (std::vector<int>{14}));
  EXPECT_EQ(object<Collector>(again, "sink_a")->ints(), (std::vector<int>{15}));
}

TEST(Subgraph, ThreeLevelsSaveAndLoad) {
  TempDir dir;
  writeFile(dir.file("scale.yaml"), kScale);
  writeFile(dir.file("middle.yaml"),
            "apex_graph: 2\n"
            "exports:\n"
            "  - {input: in, to: inner/in}\n"
            "  - {output: out, from: inner/out}\n"
            "  - {parameter: factor, to: inner/factor}\n"
            "nodes:\n"
            "  - name: inner\n    subgraph:\n"
            "      exports:\n"
            "        - {input: in, to: deep/in}\n"
            "        - {output: out, from: deep/out}\n"
            "        - {parameter: factor, to: deep/factor}\n"
            "      nodes:\n"
            "        - {name: deep, subgraph: scale.yaml}\n");
  const std::string main =
      "apex_graph: 2\n"
      "nodes:\n"
      "  - {name: feeder, type: test/Feeder}\n"
      "  - {name: top, subgraph: middle.yaml, parameters: {factor: 10}}\n"
      "  - {name: sink, type: test/Collector}\n"
      "connections:\n"
      "  - {from: feeder/out, to: top/in}\n"
      "  - {from: top/out, to: sink/in}\n";
  Graph g(testRegistry());
  auto loaded = loadText(g, dir, "main.yaml", main);
  ASSERT_TRUE(loaded) << loaded.message();
  EXPECT_EQ(std::get<int>(g.parameterValue("top/inner/deep/second", "gain").value()), 10);
  const std::string text = formatGraphText(g.describe());
  EXPECT_TRUE(Contains(text, {"subgraph: middle.yaml", "factor: 10"})) << text;
  EXPECT_EQ(run(g, "sink", 2), (std::vector<int>{30, 60}));

  // edited three levels down: the whole chain is written inline, down to that level
  ASSERT_TRUE(g.setParameter("top/inner/deep/first", "gain", "1"));
  const std::string edited = formatGraphText(g.describe());
  ASSERT_TRUE(writeFileAtomically(dir.file("edited.yaml"), edited));
  Graph again(testRegistry());
  auto reloaded = loadGraphFile(again, dir.file("edited.yaml"));
  ASSERT_TRUE(reloaded) << reloaded.message() << "\n" << edited;
  EXPECT_EQ(formatGraphText(again.describe()), edited);
  EXPECT_EQ(run(again, "sink", 2), (std::vector<int>{10, 20}));
}

TEST(Subgraph, ARenamedExportedPortIsAClearErrorAndNothingChanges) {
  TempDir dir;
  std::string broken = kScale;
  broken.replace(broken.find("from: second/out"), 16, "from: second/result");
  writeFile(dir.file("scale.yaml"), broken);
  Graph g(testRegistry());
  apex_test::add(g, "test/Ticker", "keep");
  auto loaded = loadText(g, dir, "main.yaml", twoInstances("scale.yaml"));
  ASSERT_FALSE(loaded);
  EXPECT_TRUE(Contains(loaded.message(), {"main.yaml", "line 4", "subgraph 'a'", "scale.yaml",
                                          "export 'out' stands for 'second/result'", "no output 'result'"}))
      << loaded.message();
  EXPECT_EQ(g.size(), 1u);  // all or nothing: the graph is as it was
  EXPECT_TRUE(g.nodeObject("keep"));

  writeFile(dir.file("scale.yaml"), kScale);  // and an outer connection to a port it does not export
  std::string text = twoInstances("scale.yaml");
  text.replace(text.find("to: b/in"), 8, "to: b/input");
  auto wrong = loadText(g, dir, "main.yaml", text);
  EXPECT_TRUE(Contains(wrong.message(), {"line 10", "subgraph 'b' exports no input, slot or parameter 'input'"}))
      << wrong.message();
}

TEST(Subgraph, ASubgraphFileRunsOnItsOwnAsAGraph) {
  TempDir dir;
  writeFile(dir.file("scale.yaml"), kScale);
  Graph solo(testRegistry());
  auto loaded = loadGraphFile(solo, dir.file("scale.yaml"));
  ASSERT_TRUE(loaded) << loaded.message();
  EXPECT_EQ(solo.size(), 2u);  // its exports are unused here
  EXPECT_EQ(std::get<int>(solo.parameterValue("second", "gain").value()), 2);
}

TEST(Subgraph, AFileThatIncludesItselfIsRefused) {
  TempDir dir;
  writeFile(dir.file("loop.yaml"), "apex_graph: 2\nnodes:\n  - {name: again, subgraph: loop.yaml}\n");
  Graph g(testRegistry());
  auto loaded = loadGraphFile(g, dir.file("loop.yaml"));
  EXPECT_TRUE(Contains(loaded.message(), {"subgraph 'again'", "includes itself"})) << loaded.message();
  auto old = parseGraphText("apex_graph: 1\nnodes:\n  - {name: s, subgraph: x.yaml}\n");
  EXPECT_TRUE(Contains(old.message(), {"line 3", "subgraphs need 'apex_graph: 2'"})) << old.message();
}

TEST(Subgraph, DisablingASubgraphDisablesItsNodesAndKeepsTheirOwnSetting) {
  TempDir dir;
  Graph g(testRegistry());
  ASSERT_TRUE(loadTwoScales(g, dir));
  ASSERT_TRUE(g.setEnabled("b/first", false));
  ASSERT_TRUE(g.setEnabled("b", false));
  auto enabled = [&](const std::string& name) {
    for (const auto& s : g.nodeStats())
      if (s.name == name) return s.enabled;
    return true;
  };
  EXPECT_FALSE(enabled("b/second"));
  EXPECT_TRUE(enabled("a/second"));
  EXPECT_TRUE(Contains(formatGraphText(g.describe()), {"enabled: false"}));
  ASSERT_TRUE(g.setEnabled("b", true));
  EXPECT_TRUE(enabled("b/second"));
  EXPECT_FALSE(enabled("b/first"));  // its own setting stays
}

TEST(Subgraph, RemovingASubgraphRemovesItsNodesAndConnections) {
  TempDir dir;
  Graph g(testRegistry());
  ASSERT_TRUE(loadTwoScales(g, dir));
  ASSERT_TRUE(g.removeNode("a"));
  EXPECT_EQ(g.size(), 5u);  // feeder, two sinks, b's two nodes
  EXPECT_FALSE(findNode(g.describe(), "a"));
  EXPECT_EQ(run(g, "sink_b", 1), (std::vector<int>{6}));
  EXPECT_TRUE(g.size() == 5u);
  // an exported inner node removed: its export goes with it
  ASSERT_TRUE(g.removeNode("b/second"));
  EXPECT_FALSE(g.nodeInterface("b")->findOutput("out"));
}

}  // namespace
