// Subgraphs edited: grouped and ungrouped (with restore), renamed, disabled parts, and edits
// inside a running subgraph; the graph keeps its outputs and never stalls.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "apex_test/subgraph_helpers.hpp"

namespace {

using namespace apex;
using namespace apex_test;
using namespace apex_test::subgraphs;

TEST(Subgraph, GroupingWithRestoreUndoesAnUngroupExactly) {
  TempDir dir;
  Graph g(testRegistry());
  ASSERT_TRUE(loadTwoScales(g, dir));
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
  Graph g(testRegistry());
  ASSERT_TRUE(loadTwoScales(g, dir));
  ASSERT_TRUE(g.group({"a/second"}, "stage"));  // a level down: a's exports now pass through 'stage'
  EXPECT_EQ(std::get<int>(g.parameterValue("a", "factor").value()), 5);
  EXPECT_TRUE(g.nodeInterface("a")->findOutput("out"));
  ASSERT_TRUE(g.ungroup("a/stage"));
  EXPECT_TRUE(g.nodeInterface("a")->findOutput("out"));
  EXPECT_EQ(run(g, "sink_a", 1), (std::vector<int>{15}));
}

TEST(Subgraph, RenamingANodeOrASubgraphWhileRunningKeepsItsConnectionsAndExports) {
  TempDir dir;
  Graph g(testRegistry());
  ASSERT_TRUE(loadTwoScales(g, dir));
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
