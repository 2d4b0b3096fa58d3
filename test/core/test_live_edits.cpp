// The invariants of live edits (docs/architecture.md, "Edits that cannot stall"),
// one scenario each; test_soak.cpp checks them all under random edits.
#include <gmock/gmock.h>

#include "apex_test/test_nodes.hpp"

using namespace apex_test;

namespace {

/** A source at 1 kHz from its group's timer (a driven source without a thread). */
class Timed : public Node {
 public:
  static Manifest manifest() { return Manifest("ints at 1 kHz").output<int>("out").driven(); }
  void setup() override { notifyNewData(); }
  void process() override {
    publish("out", n_++);
    notifyAfter(0.001);
  }

 private:
  int n_ = 0;
};

NodeRegistry registry() {
  NodeRegistry r = testRegistry();
  EXPECT_TRUE(r.add<Timed>("test/Timed"));
  return r;
}

// src -> r1 -> r2 -> sum.a and src -> sum.b: a join fed by one source through paths of 2 and 0 hops.
void forkJoin(Graph& g) {
  add(g, "test/Feeder", "src");
  add(g, "test/Relay", "r1");
  add(g, "test/Relay", "r2");
  add(g, "test/OptionalSum", "sum");
  add(g, "test/Collector", "sink");
  link(g, "src", "out", "r1", "in");
  link(g, "r1", "out", "r2", "in");
  link(g, "r2", "out", "sum", "a");
  link(g, "src", "out", "sum", "b");
  link(g, "sum", "sum", "sink", "in");
}

TEST(LiveEdits, AJoinNeverPairsFramesAfterALinkOnOnePathIsReconnected) {
  Graph g(registry());
  forkJoin(g);
  g.pause();
  g.start();
  object<Feeder>(g, "src")->feed(1);
  g.step();  // frame 1 waits at r1's input and at sum.b
  ASSERT_TRUE(g.disconnect("r1", "out", "r2", "in"));  // an in-flight frame may be lost on one path only...
  link(g, "r1", "out", "r2", "in");
  g.resume();
  object<Feeder>(g, "src")->feed(2);
  object<Feeder>(g, "src")->feed(3);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(2));
  ASSERT_TRUE(g.waitIdle(kWait));
  // ...so the edit drops frame 1 on both: 1+2 or 2+3 would be two frames in one sum.
  EXPECT_THAT(object<Collector>(g, "sink")->ints(), testing::ElementsAre(4, 6));
}

TEST(LiveEdits, ACutOffInputDoesNotHoldTheOtherPathsHostage) {
  Graph g(registry());
  forkJoin(g);
  g.start();
  object<Feeder>(g, "src")->feed(1);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(1));
  ASSERT_TRUE(g.disconnect("src", "out", "r1", "in"));  // sum.a is cut off from every source
  add(g, "test/Collector", "side");
  link(g, "src", "out", "side", "in");
  object<Feeder>(g, "src")->feed(2);
  object<Feeder>(g, "src")->feed(3);
  // The source goes on (it is not held by sum.b), sum sends Nothing for the frames it cannot make.
  ASSERT_TRUE(object<Collector>(g, "side")->waitFor(2));
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(3));
  EXPECT_THAT(object<Collector>(g, "sink")->ints(), testing::ElementsAre(2, -999, -999));
  auto stats = g.nodeStats(0);
  EXPECT_EQ(stats[1].name, "r1");
  EXPECT_EQ(stats[1].waiting_for, "cut off: input 'in' is not connected");
  // Put back: the paths are in step from the next frame on.
  link(g, "src", "out", "r1", "in");
  object<Feeder>(g, "src")->feed(4);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(4));
  EXPECT_EQ(object<Collector>(g, "sink")->ints().back(), 8);
}

TEST(LiveEdits, ARemovedMiddleNodeLeavesTheRestRunningAndUndoRestoresIt) {
  Graph g(registry());
  forkJoin(g);
  g.start();
  ASSERT_TRUE(g.removeNode("r2"));
  object<Feeder>(g, "src")->feed(1);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(1));
  add(g, "test/Relay", "r2");
  link(g, "r1", "out", "r2", "in");
  link(g, "r2", "out", "sum", "a");
  object<Feeder>(g, "src")->feed(5);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(2));
  EXPECT_THAT(object<Collector>(g, "sink")->ints(), testing::ElementsAre(-999, 10));
}

TEST(LiveEdits, AReadyNodeMovedToAnotherGroupStillFires) {
  Graph g(registry());
  add(g, "test/Feeder", "src");
  add(g, "test/Relay", "r");
  add(g, "test/Collector", "sink");
  link(g, "src", "out", "r", "in");
  link(g, "r", "out", "sink", "in");
  g.pause();
  g.start();
  object<Feeder>(g, "src")->feed(1);
  g.step();  // r is ready, queued on "default"
  ASSERT_TRUE(g.setThreadGroup("r", "other"));
  g.resume();
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(1)) << "r was taken off one queue and put on none";
}

TEST(LiveEdits, ABusyGroupDoesNotStarveItsTimers) {
  Graph g(registry());
  add(g, "test/Ticker", "busy");  // free-running: its group always has a node ready
  add(g, "test/Counter", "count");
  link(g, "busy", "out", "count", "in");
  add(g, "test/Timed", "timed");
  add(g, "test/Collector", "sink");
  link(g, "timed", "out", "sink", "in");
  g.start();
  EXPECT_TRUE(object<Collector>(g, "sink")->waitFor(5)) << "the timer-driven source never came back";
}

TEST(LiveEdits, StatusSaysWhatAStalledNodeWaitsFor) {
  Graph g(registry());
  add(g, "test/Feeder", "src");
  add(g, "test/Relay", "r");
  add(g, "test/OptionalSum", "sum");
  add(g, "test/Feeder", "other");
  link(g, "src", "out", "r", "in");
  link(g, "r", "out", "sum", "a");
  link(g, "other", "out", "sum", "b");
  g.start();
  object<Feeder>(g, "src")->feed(1);  // reaches sum.a; sum.b waits for 'other', which never sends
  ASSERT_TRUE(g.waitIdle(kWait));
  auto stats = g.nodeStats(0);
  EXPECT_EQ(stats[2].waiting_for, "waiting for input 'b' from 'other'");
  EXPECT_EQ(stats[1].waiting_for, "waiting for 'sum' to read 'out'");
  EXPECT_EQ(stats[3].waiting_for, "waiting for new data");
  EXPECT_EQ(g.nodeStats(60)[2].waiting_for, "") << "idle for less than a minute: not stalled";
}

}  // namespace

namespace {

TEST(LiveEdits, ACutOffParameterOutputNeitherFiresItsReceiverNorUnbalancesIt) {
  Graph g(registry());
  add(g, "test/Feeder", "src");
  add(g, "test/Gain", "gain");
  add(g, "test/Collector", "values");
  ASSERT_TRUE(g.setInteractive("gain", "gain", true));
  link(g, "src", "out", "gain", "in");
  link(g, "gain", "gain", "values", "in");
  g.start();
  object<Feeder>(g, "src")->feed(1);
  ASSERT_TRUE(object<Collector>(g, "values")->waitFor(1));
  ASSERT_TRUE(g.disconnect("src", "out", "gain", "in"));  // gain and values are cut off
  ASSERT_TRUE(g.setParameter("gain", "gain", "5"));  // published to a receiver that cannot fire
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(object<Collector>(g, "values")->size(), 1u) << "a cut-off node fired";
  link(g, "src", "out", "gain", "in");
  for (int i = 2; i <= 4; ++i) {
    object<Feeder>(g, "src")->feed(i);
    ASSERT_TRUE(object<Collector>(g, "values")->waitFor(static_cast<std::size_t>(i))) << "values stalled after frame " << i;
  }
  EXPECT_EQ(object<Collector>(g, "values")->ints().back(), 5);
}

}  // namespace
