// Subgraphs: a group of nodes used as one node through the ports, parameters and
// events it exports; inline or from a file; flattened, so they run like any node.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "apex/core/file_roots.hpp"
#include "apex/core/graph.hpp"
#include "apex/core/graph_file.hpp"
#include "apex_test/graph_file_helpers.hpp"
#include "apex_test/test_nodes.hpp"

namespace {

using namespace apex;
using apex_test::Collector;
using apex_test::Contains;
using apex_test::Feeder;
using apex_test::object;
using apex_test::TempDir;
using apex_test::testRegistry;
using apex_test::writeFile;

// in × a × b, as a file other graphs use
const char* kScale =
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

std::string twoInstances(const std::string& ref) {
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
std::vector<int> run(Graph& g, const std::string& sink, int n = 4) {
  g.start();
  for (int i = 1; i <= n; ++i) object<Feeder>(g, "feeder")->feed(i);
  EXPECT_TRUE(object<Collector>(g, sink)->waitFor(n));
  EXPECT_TRUE(g.waitIdle(apex_test::kWait));
  g.stop();
  return object<Collector>(g, sink)->ints();
}

Result<LoadReport> loadText(Graph& g, TempDir& dir, const std::string& name, const std::string& text) {
  writeFile(dir.file(name), text);
  return loadGraphFile(g, dir.file(name));
}

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
  writeFile(dir.file("scale.yaml"), kScale);
  Graph g(testRegistry());
  auto loaded = loadText(g, dir, "main.yaml", twoInstances("scale.yaml"));
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
  writeFile(dir.file("scale.yaml"), kScale);
  Graph g(testRegistry());
  auto loaded = loadText(g, dir, "main.yaml", twoInstances("scale.yaml"));
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
  writeFile(dir.file("scale.yaml"), kScale);
  Graph g(testRegistry());
  ASSERT_TRUE(loadText(g, dir, "main.yaml", twoInstances("scale.yaml")));
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
  writeFile(dir.file("scale.yaml"), kScale);
  Graph g(testRegistry());
  ASSERT_TRUE(loadText(g, dir, "main.yaml", twoInstances("scale.yaml")));
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
  writeFile(dir.file("scale.yaml"), kScale);
  Graph g(testRegistry());
  ASSERT_TRUE(loadText(g, dir, "main.yaml", twoInstances("scale.yaml")));
  ASSERT_TRUE(g.removeNode("a"));
  EXPECT_EQ(g.size(), 5u);  // feeder, two sinks, b's two nodes
  EXPECT_FALSE(findNode(g.describe(), "a"));
  EXPECT_EQ(run(g, "sink_b", 1), (std::vector<int>{6}));
  EXPECT_TRUE(g.size() == 5u);
  // an exported inner node removed: its export goes with it
  ASSERT_TRUE(g.removeNode("b/second"));
  EXPECT_FALSE(g.nodeInterface("b")->findOutput("out"));
}

TEST(Subgraph, GroupingWithRestoreUndoesAnUngroupExactly) {
  TempDir dir;
  writeFile(dir.file("scale.yaml"), kScale);
  Graph g(testRegistry());
  ASSERT_TRUE(loadText(g, dir, "main.yaml", twoInstances("scale.yaml")));
  ASSERT_TRUE(g.setEnabled("a", false));
  ASSERT_TRUE(g.setUi("a", "{x: 40, y: 80}"));
  const std::string before = formatGraphText(g.describe());  // a file reference, factor 5, disabled
  ASSERT_TRUE(g.ungroup("a"));
  auto enabled = [&](const std::string& name) {
    for (const auto& st : g.nodeStats())
      if (st.name == name) return st.enabled;
    return false;
  };
  EXPECT_TRUE(enabled("first"));  // no longer inside a disabled subgraph
  ASSERT_TRUE(g.group({"first", "second"}, "a", /*restore=*/true));
  EXPECT_EQ(formatGraphText(g.describe()), before);  // its file, exported parameter, state and place
  EXPECT_FALSE(enabled("a/first"));
  EXPECT_EQ(run(g, "sink_b", 2), (std::vector<int>{6, 12}));
  for (int got : object<Collector>(g, "sink_a")->ints()) EXPECT_EQ(got, -999) << "the restored subgraph is disabled: Nothing";

  // Without restore (a new grouping), or once the nodes differ: exports from the crossing links only
  ASSERT_TRUE(g.ungroup("a"));
  ASSERT_TRUE(g.group({"first", "second"}, "a"));
  EXPECT_NE(formatGraphText(g.describe()), before);
  EXPECT_FALSE(g.nodeInterface("a")->findParam("factor"));
  ASSERT_TRUE(g.ungroup("a"));
  ASSERT_TRUE(g.group({"first"}, "a", /*restore=*/true));
  EXPECT_FALSE(g.nodeInterface("a")->findParam("factor"));
}

TEST(Subgraph, GroupAndUngroupWhileRunningKeepTheOutputsAndGiveTheFlatGraphBack) {
  Graph g(testRegistry());
  apex_test::add(g, "test/Feeder", "feeder");
  apex_test::add(g, "test/Gain", "first");
  apex_test::add(g, "test/Gain", "second");
  apex_test::add(g, "test/Collector", "sink");
  apex_test::add(g, "test/Collector", "tap");
  ASSERT_TRUE(g.setParameter("first", "gain", "3"));
  ASSERT_TRUE(g.setParameter("second", "gain", "2"));
  apex_test::link(g, "feeder", "out", "first", "in");
  apex_test::link(g, "first", "out", "second", "in");
  apex_test::link(g, "second", "out", "sink", "in");
  apex_test::link(g, "first", "out", "tap", "in");  // an inner sender also feeds outside
  const std::string flat = formatGraphText(g.describe());
  g.start();
  auto* feeder = object<Feeder>(g, "feeder");
  auto* sink = object<Collector>(g, "sink");
  feeder->feed(1);
  ASSERT_TRUE(sink->waitFor(1));

  auto grouped = g.group({"first", "second"}, "scale");
  ASSERT_TRUE(grouped) << grouped.message();
  feeder->feed(2);  // data flows on through the same edges: nothing was rebuilt
  ASSERT_TRUE(sink->waitFor(2));
  const std::string text = formatGraphText(g.describe());
  // exports named after the inner ports, the node's name added where two share one
  EXPECT_TRUE(Contains(
      text, {"name: scale", "{input: in, to: first/in}", "{output: out, from: first/out}",
             "{output: second_out, from: second/out}", "{from: feeder/out, to: scale/in}",
             "{from: scale/second_out, to: sink/in}", "{from: scale/out, to: tap/in}", "{from: first/out, to: second/in}"}))
      << text;
  EXPECT_TRUE(g.setParameter("scale/first", "gain", "3"));
  EXPECT_TRUE(g.nodeInterface("scale")->findInput("in"));
  // the grouped graph, saved and loaded, runs the same
  Graph again(testRegistry());
  ASSERT_TRUE(again.load(parseGraphText(text).value()));
  EXPECT_EQ(formatGraphText(again.describe()), text);
  EXPECT_EQ(run(again, "sink", 2), (std::vector<int>{6, 12}));

  auto ungrouped = g.ungroup("scale");
  ASSERT_TRUE(ungrouped) << ungrouped.message();
  feeder->feed(3);
  ASSERT_TRUE(sink->waitFor(3));
  ASSERT_TRUE(g.waitIdle(apex_test::kWait));
  g.stop();
  EXPECT_EQ(sink->ints(), (std::vector<int>{6, 12, 18}));
  EXPECT_EQ(formatGraphText(g.describe()), flat);  // the round trip gives the flat graph back

  auto apart = g.group({"first", "nope"}, "x");
  EXPECT_TRUE(Contains(apart.message(), {"cannot group into 'x'", "no node named 'nope'"})) << apart.message();
  auto taken = g.group({"first"}, "sink");
  EXPECT_TRUE(Contains(taken.message(), {"a node named 'sink' already exists"})) << taken.message();
  EXPECT_TRUE(Contains(g.ungroup("first").message(), {"not a subgraph"}));
}

TEST(Subgraph, GroupingInsideASubgraphAndUngroupingKeepTheExportsWorking) {
  TempDir dir;
  writeFile(dir.file("scale.yaml"), kScale);
  Graph g(testRegistry());
  ASSERT_TRUE(loadText(g, dir, "main.yaml", twoInstances("scale.yaml")));
  ASSERT_TRUE(g.group({"a/second"}, "stage"));  // a level down: a's exports now pass through 'stage'
  EXPECT_EQ(std::get<int>(g.parameterValue("a", "factor").value()), 5);
  EXPECT_TRUE(g.nodeInterface("a")->findOutput("out"));
  ASSERT_TRUE(g.ungroup("a/stage"));
  EXPECT_TRUE(g.nodeInterface("a")->findOutput("out"));
  EXPECT_EQ(run(g, "sink_a", 1), (std::vector<int>{15}));
}

TEST(Subgraph, RenamingANodeOrASubgraphWhileRunningKeepsItsConnectionsAndExports) {
  TempDir dir;
  writeFile(dir.file("scale.yaml"), kScale);
  Graph g(testRegistry());
  ASSERT_TRUE(loadText(g, dir, "main.yaml", twoInstances("scale.yaml")));
  g.start();
  auto* feeder = object<Feeder>(g, "feeder");
  auto* sink = object<Collector>(g, "sink_a");
  feeder->feed(1);
  ASSERT_TRUE(sink->waitFor(1));

  auto inner = g.rename("a/second", "last");  // named by a's exports 'out' and 'factor'
  ASSERT_TRUE(inner) << inner.message();
  auto outer = g.rename("a", "five");
  ASSERT_TRUE(outer) << outer.message();
  ASSERT_TRUE(g.rename("sink_a", "sink"));
  feeder->feed(2);  // the same edges: nothing was rebuilt
  ASSERT_TRUE(sink->waitFor(2));
  EXPECT_EQ(std::get<int>(g.parameterValue("five", "factor").value()), 5);
  EXPECT_EQ(std::get<int>(g.parameterValue("five/last", "gain").value()), 5);
  const std::string text = formatGraphText(g.describe());
  EXPECT_TRUE(Contains(text, {"name: five", "{output: out, from: last/out}", "{parameter: factor, to: last/gain",
                              "{from: first/out, to: last/in}", "{from: five/out, to: sink/in}"}))
      << text;
  EXPECT_FALSE(Contains(text, {"name: a,"})) << text;

  EXPECT_TRUE(Contains(g.rename("b", "five").message(), {"cannot rename 'b'", "a node named 'five' already exists"}));
  EXPECT_TRUE(Contains(g.rename("nope", "x").message(), {"no node named 'nope'"}));
  EXPECT_TRUE(Contains(g.rename("b", "x/y").message(), {"a name, not a path"}));
  EXPECT_TRUE(Contains(g.rename("b", "two words").message(), {"node name 'two words'"}));
  ASSERT_TRUE(g.waitIdle(apex_test::kWait));
  g.stop();
  EXPECT_EQ(sink->ints(), (std::vector<int>{15, 30}));
}

TEST(Subgraph, LiveEditsInsideARunningSubgraphNeverStallTheGraph) {
  TempDir dir;
  writeFile(dir.file("scale.yaml"), kScale);
  std::string main = twoInstances("scale.yaml");
  main.replace(main.find("test/Feeder"), 11, "test/Ticker");  // free-running: data always flows
  Graph g(testRegistry());
  auto loaded = loadText(g, dir, "main.yaml", main);
  ASSERT_TRUE(loaded) << loaded.message();
  auto* sink_b = object<Collector>(g, "sink_b");
  auto flows = [&] {
    const std::size_t before = sink_b->size();
    return sink_b->waitFor(before + 5);
  };
  g.start();
  ASSERT_TRUE(flows());
  for (int round = 0; round < 20; ++round) {  // each edit while the other instance and the feeder run on
    ASSERT_TRUE(g.disconnect("a/first", "out", "a/second", "in"));
    ASSERT_TRUE(flows()) << "round " << round << ": a cut inside 'a' stalled 'b'";
    ASSERT_TRUE(g.connect("a/first", "out", "a/second", "in"));
    ASSERT_TRUE(g.removeNode("a/second"));
    ASSERT_TRUE(flows()) << "round " << round << ": removing a node inside 'a' stalled 'b'";
    ASSERT_TRUE(g.addNode("test/Gain", "a/second"));
    ASSERT_TRUE(g.connect("a/first", "out", "a/second", "in"));
    ASSERT_TRUE(g.connect("a/second", "out", "sink_a", "in"));
    ASSERT_TRUE(g.setEnabled("a", round % 2 == 0));
    ASSERT_TRUE(g.setParameter("b", "factor", std::to_string(round % 5 + 1)));
    ASSERT_TRUE(flows()) << "round " << round;
  }
  ASSERT_TRUE(g.setEnabled("a", true));
  auto* sink_a = object<Collector>(g, "sink_a");
  const std::size_t before = sink_a->size();
  EXPECT_TRUE(sink_a->waitFor(before + 5)) << "the edited subgraph runs again once whole";
  g.stop();
}

}  // namespace

TEST(Subgraph, GroupingInsideUnderTheParentsOwnNameKeepsEveryNode) {
  // s/s begins where s begins (at its first node): both used to take one place in the
  // description, and the outer one with all its nodes was left out of ~get_graph and saves
  Graph g(testRegistry());
  apex_test::add(g, "test/Feeder", "feeder");
  apex_test::add(g, "test/Gain", "first");
  apex_test::add(g, "test/Collector", "sink");
  ASSERT_TRUE(g.setParameter("first", "gain", "3"));
  apex_test::link(g, "feeder", "out", "first", "in");
  apex_test::link(g, "first", "out", "sink", "in");
  ASSERT_TRUE(g.group({"first", "sink"}, "s"));
  auto inner = g.group({"s/first"}, "s");  // s/s: the name is free one level down
  ASSERT_TRUE(inner) << inner.message();
  const std::string text = formatGraphText(g.describe());
  EXPECT_TRUE(Contains(text, {"name: s", "name: first", "name: sink"})) << text;
  Graph again(testRegistry());  // saved and loaded: the same graph, and it runs
  auto loaded = again.load(parseGraphText(text).value());
  ASSERT_TRUE(loaded) << loaded.message() << "\n" << text;
  EXPECT_EQ(formatGraphText(again.describe()), text);
  EXPECT_EQ(run(again, "s/sink", 2), (std::vector<int>{3, 6}));
}
