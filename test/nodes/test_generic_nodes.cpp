// Generic nodes: Add, Throttle, TimeSync, Select, Counter, Relay.
#include <gmock/gmock.h>

#include "apex_nodes/types.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using ::testing::HasSubstr;

namespace {

std::shared_ptr<const apex_nodes::Cloud> stamped(double t) {
  auto c = std::make_shared<apex_nodes::Cloud>();
  c->header.stamp = ros::Time(t);
  c->points = std::make_shared<pcl::PCLPointCloud2>();
  return c;
}

TEST(GenericNodes, AddSums) {
  NodeHarness h("apex_nodes/Add", {"a", "b"}, "sum");
  EXPECT_EQ(*h.run({Message::make(1.5), Message::make(2.25)}).as<double>(), 3.75);
}

TEST(GenericNodes, ThrottlePassesAtMostTheRate) {
  NodeHarness h("apex_nodes/Throttle", {"in"}, "out");
  h.set("rate", "0.01");  // one per 100 s: only the first passes here
  EXPECT_EQ(*h.run({Message::make(1)}).as<int>(), 1);
  EXPECT_TRUE(h.run({Message::make(2)}).isNothing());
  EXPECT_TRUE(h.run({Message::make(3)}).isNothing());
}

TEST(GenericNodes, TimeSyncPairsByStamp) {
  NodeHarness h("apex_nodes/TimeSync", {"a", "b"}, "b");
  h.set("tolerance", "0.05");
  const auto b = stamped(10.03);
  EXPECT_EQ(h.run({Message::share<apex_nodes::Cloud>(stamped(10.0)), Message::share<apex_nodes::Cloud>(b)}).raw(), b.get());
  EXPECT_TRUE(
      h.run({Message::share<apex_nodes::Cloud>(stamped(10.0)), Message::share<apex_nodes::Cloud>(stamped(10.2))}).isNothing());
  EXPECT_TRUE(h.run({Message::make(1), Message::share<apex_nodes::Cloud>(b)}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("cannot read a stamp from a int"));
}

TEST(GenericNodes, TimeSyncTakesAsManyInputsAsItIsGiven) {
  NodeHarness h("apex_nodes/TimeSync", {"a", "b", "c"}, "c", {{"inputs", "3"}});
  const auto c = stamped(10.04);
  auto cloud = [](std::shared_ptr<const apex_nodes::Cloud> p) { return Message::share<apex_nodes::Cloud>(p); };
  EXPECT_EQ(h.run({cloud(stamped(10.0)), cloud(stamped(10.02)), cloud(c)}).raw(), c.get());
  EXPECT_TRUE(h.run({cloud(stamped(10.0)), cloud(stamped(10.02)), cloud(stamped(10.2))}).isNothing());
  ASSERT_TRUE(h.graph().setParameter("node", "inputs", "2"));  // c goes, with its connections: no stall
  EXPECT_EQ(h.graph().describe().connections.size(), 2u + 0u);  // in0 -> a, in1 -> b
}

TEST(GenericNodes, SelectPassesTheChosenInput) {
  NodeHarness h("apex_nodes/Select", {"in_0", "in_1", "in_2"}, "out", {{"inputs", "3"}});
  h.set("choice", "2");
  EXPECT_EQ(*h.run({Message::make(1), Message::make(2), Message::make(3)}).as<int>(), 3);
  h.set("choice", "0");
  EXPECT_EQ(*h.run({Message::make(4), Message::make(5), Message::make(6)}).as<int>(), 4);
}

TEST(GenericNodes, CounterCountsAndResets) {
  NodeHarness h("apex_nodes/Counter", {"in"}, "count");
  EXPECT_EQ(*h.run({Message::make(7)}).as<int>(), 1);
  EXPECT_EQ(*h.run({Message::make(7)}).as<int>(), 2);
  ASSERT_TRUE(h.graph().fireSlot("node", "reset"));
  ASSERT_TRUE(h.graph().waitIdle(kWait));
  EXPECT_EQ(*h.run({Message::make(7)}).as<int>(), 1);
}

TEST(GenericNodes, RelayPassesTheSameObject) {
  NodeHarness h("apex_nodes/Relay", {"in"}, "out");
  auto payload = std::make_shared<const std::string>("x");
  EXPECT_EQ(h.run(payload).raw(), payload.get());
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

namespace {

TEST(GenericNodes, ScaleMultiplies) {
  NodeHarness h("apex_nodes/Scale", {"in"}, "out");
  h.set("factor", "-2.5");
  EXPECT_EQ(*h.run({Message::make(4.0)}).as<double>(), -10.0);
}

TEST(GenericNodes, PrintLogsNumbersAndTypeNames) {
  std::mutex m;
  std::vector<std::string> lines;
  setLogSink([&](LogLevel, const std::string& node, const std::string& text) {
    std::lock_guard<std::mutex> l(m);
    if (node == "node") lines.push_back(text);
  });
  {
    Graph g(pluginRegistry());
    add(g, "test/MessageFeeder", "in0");
    add(g, "apex_nodes/Print", "node");
    link(g, "in0", "out", "node", "in");
    ASSERT_TRUE(g.setParameter("node", "prefix", "'value: '"));
    g.start();
    object<MessageFeeder>(g, "in0")->feed(Message::make(42));
    object<MessageFeeder>(g, "in0")->feed(Message::make(apex::Color{1, 2, 3}));
    ASSERT_TRUE(g.waitIdle(kWait));
  }
  setLogSink(nullptr);
  std::lock_guard<std::mutex> l(m);
  EXPECT_THAT(lines, ::testing::ElementsAre("value: 42", "value: <color>"));
}

TEST(GenericNodes, ClockTicksAtItsRate) {
  Graph g(pluginRegistry());
  add(g, "apex_nodes/Clock", "clock");
  add(g, "test/Collector", "sink");
  link(g, "clock", "count", "sink", "in");
  ASSERT_TRUE(g.setParameter("clock", "rate", "200"));
  const auto t0 = std::chrono::steady_clock::now();
  g.start();
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(10));
  EXPECT_GE(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 0.04);  // 10 ticks 5 ms apart
  auto ticks = object<Collector>(g, "sink")->ints();
  for (std::size_t i = 0; i < 10; ++i) EXPECT_EQ(ticks[i], static_cast<int>(i));
}

}  // namespace
