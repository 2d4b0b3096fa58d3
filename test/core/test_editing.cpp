// Editing while the graph runs: no deadlock, unrelated paths lose nothing,
// removed connections drop their pending message.
#include <gmock/gmock.h>

#include <random>
#include <thread>

#include "apex_test/test_nodes.hpp"

using namespace apex_test;

namespace {

TEST(Editing, AnUnconnectedMandatoryInputHoldsTheNode) {
  Graph g(testRegistry());
  add(g, "test/Relay", "r");
  add(g, "test/Collector", "sink");
  link(g, "r", "out", "sink", "in");
  g.start();
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(g.nodeStats()[0].firings, 0u);
}

TEST(Editing, ARemovedConnectionDropsItsPendingMessage) {
  Graph g(testRegistry());
  add(g, "test/Feeder", "src");
  add(g, "test/Relay", "r");
  add(g, "test/Collector", "sink");
  link(g, "src", "out", "r", "in");
  link(g, "r", "out", "sink", "in");
  g.pause();
  g.start();
  object<Feeder>(g, "src")->feed(1);
  g.step();  // 1 now waits at r's input
  ASSERT_TRUE(g.disconnect("src", "out", "r", "in"));
  link(g, "src", "out", "r", "in");
  g.resume();
  object<Feeder>(g, "src")->feed(2);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(1));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(object<Collector>(g, "sink")->ints(), std::vector<int>{2});
}

TEST(Editing, RemovingABusyReceiverFreesItsSource) {
  Graph g(testRegistry());
  add(g, "test/Feeder", "src");
  add(g, "test/Relay", "a");
  add(g, "test/Relay", "b");
  add(g, "test/Collector", "sink");
  link(g, "src", "out", "a", "in");
  link(g, "src", "out", "b", "in");
  link(g, "a", "out", "sink", "in");
  // b's input is never read (b has no receiver, so it fires only while connected)
  g.start();
  object<Feeder>(g, "src")->feed(1);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(1));
  ASSERT_TRUE(g.removeNode("b"));
  object<Feeder>(g, "src")->feed(2);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(2));
}

/** Edits from another thread while data flows through an unrelated path. */
TEST(Editing, StressEditsWhileDataFlows) {
  Graph g(testRegistry());
  add(g, "test/Feeder", "src");
  add(g, "test/Relay", "r1", "g1");
  add(g, "test/Gain", "r2", "g2");
  add(g, "test/Collector", "sink");
  link(g, "src", "out", "r1", "in");
  link(g, "r1", "out", "r2", "in");
  link(g, "r2", "out", "sink", "in");
  g.start();

  std::atomic<bool> done{false};
  std::atomic<int> edits{0};
  std::thread editor([&] {
    std::mt19937 rng(42);
    const char* groups[] = {"default", "g1", "g2", "g3"};
    for (int i = 0; i < 300 || !done; ++i) {
      const std::string t = "t" + std::to_string(i), x = "x" + std::to_string(i), c = "c" + std::to_string(i);
      const std::string grp = groups[rng() % 4];
      // a side path with its own free-running source, built and torn down
      EXPECT_TRUE(g.addNode("test/Ticker", t, grp));
      EXPECT_TRUE(g.addNode("test/Gain", x, groups[rng() % 4]));
      EXPECT_TRUE(g.addNode("test/Collector", c, groups[rng() % 4]));
      EXPECT_TRUE(g.connect(t, "out", x, "in"));
      EXPECT_TRUE(g.connect(x, "out", c, "in"));
      EXPECT_TRUE(g.setParameter(x, "gain", std::to_string(int(rng() % 10))));
      // touch the main path without changing what it computes
      EXPECT_TRUE(g.connect("r1", "out", c + "_tap", "in").isOk() == false);
      EXPECT_TRUE(g.setThreadGroup("r1", groups[rng() % 4]));
      EXPECT_TRUE(g.setParameter("r2", "gain", "1"));
      EXPECT_TRUE(g.addNode("test/Collector", c + "_tap", grp));
      EXPECT_TRUE(g.connect("r2", "out", c + "_tap", "in"));  // a second receiver of the main path
      EXPECT_TRUE(g.setEnabled(x, rng() % 2));
      EXPECT_TRUE(g.fireSlot(x, "disable"));
      EXPECT_TRUE(g.disconnect(t, "out", x, "in"));
      EXPECT_TRUE(g.removeNode(c + "_tap"));
      EXPECT_TRUE(g.removeNode(t));
      EXPECT_TRUE(g.removeNode(x));
      EXPECT_TRUE(g.removeNode(c));
      edits += 17;
    }
  });
  constexpr int kMessages = 3000;
  for (int i = 0; i < kMessages; ++i) object<Feeder>(g, "src")->feed(i);
  const bool all = object<Collector>(g, "sink")->waitFor(kMessages, 60.0);
  done = true;
  editor.join();
  ASSERT_TRUE(all) << "received " << object<Collector>(g, "sink")->size() << " of " << kMessages;
  auto got = object<Collector>(g, "sink")->ints();
  for (int i = 0; i < kMessages; ++i) ASSERT_EQ(got[i], i) << "lost or reordered at " << i;
  EXPECT_GE(edits.load(), 300 * 17);
  EXPECT_EQ(g.size(), 4u);
  EXPECT_EQ(g.describe().connections.size(), 3u);
  // still flowing after all that
  object<Feeder>(g, "src")->feed(kMessages);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(kMessages + 1));
}

}  // namespace
