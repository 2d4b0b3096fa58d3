// Triggers and slots, enable/disable, and parameters as ports.
#include <gmock/gmock.h>

#include "apex_test/test_nodes.hpp"
#include "graph_text.hpp"

using namespace apex_test;
using ::testing::HasSubstr;

namespace {

std::string paramText(Graph& g, const std::string& node, const std::string& param) {
  for (auto& n : g.describe().nodes)
    if (n.name == node)
      for (auto& [name, text] : n.parameters)
        if (name == param) return text;
  return "?";
}

TEST(Events, ATriggerFiresConnectedSlotsOnTheirOwnGroup) {
  Graph g(testRegistry());
  add(g, "test/Feeder", "src");
  add(g, "test/Counter", "c", "one");
  add(g, "test/Counter", "other", "two");
  add(g, "test/Collector", "unused");
  link(g, "src", "out", "c", "in");
  link(g, "c", "every_n", "other", "reset");  // every 3rd firing of c resets `other`
  g.start();
  for (int i = 0; i < 9; ++i) object<Feeder>(g, "src")->feed(i);
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(object<Counter>(g, "c")->count.load(), 9);
  EXPECT_EQ(object<Counter>(g, "other")->resets.load(), 3);
}

TEST(Events, FireSlotFromOutsideAndUnknownSlotsAreNamed) {
  Graph g(testRegistry());
  add(g, "test/Counter", "c");
  g.start();
  ASSERT_TRUE(g.fireSlot("c", "reset"));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(object<Counter>(g, "c")->resets.load(), 1);
  auto st = g.fireSlot("c", "rest");
  EXPECT_THAT(st.message(), HasSubstr("has no slot 'rest' (slots: enable, disable, reset)"));
}

TEST(Events, ProcessedFiresAfterEachProcess) {
  Graph g(testRegistry());
  add(g, "test/Feeder", "src");
  add(g, "test/Collector", "sink");
  add(g, "test/Counter", "c");
  link(g, "src", "out", "sink", "in");
  link(g, "sink", "processed", "c", "reset");
  g.start();
  for (int i = 0; i < 5; ++i) object<Feeder>(g, "src")->feed(i);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(5));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(object<Counter>(g, "c")->resets.load(), 5);
}

TEST(Events, ASlotsErrorStaysThroughDataUntilASlotRunsFine) {
  // The Optimizer's start without a range: the panel polls the error; data flowing through the
  // node meanwhile must not take it away before anyone saw it.
  Graph g(testRegistry());
  add(g, "test/Feeder", "src");
  add(g, "test/Thrower", "t");
  add(g, "test/Collector", "sink");
  link(g, "src", "out", "t", "in");
  link(g, "t", "out", "sink", "in");
  g.start();
  ASSERT_TRUE(g.fireSlot("t", "start"));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_THAT(g.nodeStats()[1].error, HasSubstr("slot 'start' threw: give throw_on first"));
  object<Feeder>(g, "src")->feed(1);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(1));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_THAT(g.nodeStats()[1].error, HasSubstr("slot 'start' threw")) << "a good firing took the slot's error away";
  ASSERT_TRUE(g.setParameter("t", "throw_on", "5"));
  ASSERT_TRUE(g.fireSlot("t", "start"));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(g.nodeStats()[1].error, "") << "the slot ran fine";
  // a firing's own error is a firing's: the next good one clears it, as before
  object<Feeder>(g, "src")->feed(5);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(2));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_THAT(g.nodeStats()[1].error, HasSubstr("bad value 5"));
  object<Feeder>(g, "src")->feed(6);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(3));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(g.nodeStats()[1].error, "");
}

TEST(Events, ADisabledNodeSendsNothingAndTheSlotsToggleIt) {
  Graph g(testRegistry());
  add(g, "test/Feeder", "src");
  add(g, "test/Gain", "gain");
  add(g, "test/Collector", "sink");
  link(g, "src", "out", "gain", "in");
  link(g, "gain", "out", "sink", "in");
  g.start();
  ASSERT_TRUE(g.setEnabled("gain", false));
  object<Feeder>(g, "src")->feed(1);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(1));
  ASSERT_TRUE(g.fireSlot("gain", "enable"));
  ASSERT_TRUE(g.waitIdle(kWait));
  object<Feeder>(g, "src")->feed(2);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(2));
  EXPECT_EQ(object<Collector>(g, "sink")->ints(), (std::vector<int>{-999, 2}));
  ASSERT_TRUE(g.fireSlot("gain", "disable"));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_FALSE(g.describe().nodes[1].enabled);
}

TEST(Events, ADisabledSourceStopsAndResumes) {
  Graph g(testRegistry());
  add(g, "test/Ticker", "tick");
  add(g, "test/Collector", "sink");
  link(g, "tick", "out", "sink", "in");
  ASSERT_TRUE(g.setEnabled("tick", false));
  g.start();
  ASSERT_TRUE(g.waitIdle(kWait));  // a disabled free-running source does not spin
  EXPECT_EQ(object<Collector>(g, "sink")->size(), 0u);
  ASSERT_TRUE(g.setEnabled("tick", true));
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(100));
  ASSERT_TRUE(g.setEnabled("tick", false));
  ASSERT_TRUE(g.waitIdle(kWait));
  const auto n = object<Collector>(g, "sink")->size();
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(object<Collector>(g, "sink")->size(), n);
}

TEST(ParamPorts, LinkedParametersStayInSync) {
  Graph g(testRegistry());
  ASSERT_TRUE(buildFromText(g, R"(
    nodes:
      - {name: a, type: test/Gain, interactive: [gain]}
      - {name: b, type: test/Gain, interactive: [gain]}
    connections: [{from: a/gain, to: b/gain}, {from: b/gain, to: a/gain}])"));
  g.start();
  ASSERT_EQ(g.setParameter("a", "gain", "7").value(), "7");
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(paramText(g, "b", "gain"), "7");
  ASSERT_TRUE(g.setParameter("b", "gain", "-3"));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(paramText(g, "a", "gain"), "-3");
}

TEST(ParamPorts, DataDrivesAParameterWithoutHoldingTheNodeBack) {
  Graph g(testRegistry());
  ASSERT_TRUE(buildFromText(g, R"(
    nodes:
      - {name: values, type: test/Feeder}
      - {name: data, type: test/Feeder}
      - {name: gain, type: test/Gain, interactive: [gain]}
      - {name: sink, type: test/Collector}
    connections: [{from: values/out, to: gain/gain}, {from: data/out, to: gain/in}, {from: gain/out, to: sink/in}])"));
  g.start();
  object<Feeder>(g, "data")->feed(2);  // no value at the parameter input yet: fires anyway
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(1));
  object<Feeder>(g, "values")->feed(10);
  ASSERT_TRUE(g.waitIdle(kWait));
  object<Feeder>(g, "data")->feed(2);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(2));
  EXPECT_EQ(object<Collector>(g, "sink")->ints(), (std::vector<int>{2, 20}));
  object<Feeder>(g, "values")->feed(1000);  // out of range: refused, the old value stays
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(paramText(g, "gain", "gain"), "10");
  EXPECT_THAT(g.nodeStats()[2].error, HasSubstr("out of range"));
}

TEST(ParamPorts, AParameterOutputCarriesTheValueOnEveryFiring) {
  Graph g(testRegistry());
  ASSERT_TRUE(buildFromText(g, R"(
    nodes:
      - {name: src, type: test/Feeder}
      - {name: gain, type: test/Gain, parameters: {gain: 4}, interactive: [gain]}
      - {name: values, type: test/Collector}
    connections: [{from: src/out, to: gain/in}, {from: gain/gain, to: values/in}])"));
  g.start();
  object<Feeder>(g, "src")->feed(1);
  ASSERT_TRUE(object<Collector>(g, "values")->waitFor(1));
  ASSERT_TRUE(g.waitIdle(kWait));
  object<Feeder>(g, "src")->feed(1);
  ASSERT_TRUE(object<Collector>(g, "values")->waitFor(2));
  for (int v : object<Collector>(g, "values")->ints()) EXPECT_EQ(v, 4);
}

}  // namespace
