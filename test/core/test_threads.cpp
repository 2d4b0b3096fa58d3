// Thread groups: each its own scheduler; pipelining across groups; moving a
// node while the graph runs; pause, resume and single-step.
#include <gmock/gmock.h>

#include <thread>

#include "apex_test/test_nodes.hpp"
#include "graph_text.hpp"

using namespace apex_test;

namespace {

/** Records the thread each firing ran on. */
struct WhereAmI : Node {
  static Manifest manifest() { return Manifest().input<int>("in").output<int>("out"); }
  void process() override {
    {
      std::lock_guard<std::mutex> l(m);
      threads.push_back(std::this_thread::get_id());
    }
    publish("out", *input<int>("in"));
  }
  std::vector<std::thread::id> seen() {
    std::lock_guard<std::mutex> l(m);
    return threads;
  }
  std::mutex m;
  std::vector<std::thread::id> threads;
};

/** A slot that works 50 us (busy, as a node computing). */
struct SlowSlot : Node {
  static Manifest manifest() { return Manifest().slot("work", &SlowSlot::work); }
  void process() override {}
  void work() {
    const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(50);
    while (std::chrono::steady_clock::now() < until) {
    }
    ++runs;
  }
  std::atomic<int> runs{0};
};

struct Threads : ::testing::Test {
  Graph g{testRegistry()};
  void SetUp() override {
    ASSERT_TRUE(g.registry().add<WhereAmI>("test/WhereAmI"));
    ASSERT_TRUE(g.registry().add<SlowSlot>("test/SlowSlot"));
  }
  Feeder* src() { return object<Feeder>(g, "src"); }
  Collector* sink() { return object<Collector>(g, "sink"); }
};

TEST_F(Threads, EachGroupRunsOnItsOwnThread) {
  ASSERT_TRUE(buildFromText(g, R"(
    nodes:
      - {name: src, type: test/Feeder}
      - {name: a, type: test/WhereAmI, thread_group: vision}
      - {name: b, type: test/WhereAmI, thread_group: lidar}
      - {name: sink, type: test/Collector}
    connections: [{from: src/out, to: a/in}, {from: a/out, to: b/in}, {from: b/out, to: sink/in}])"));
  g.start();
  for (int i = 0; i < 20; ++i) src()->feed(i);
  ASSERT_TRUE(sink()->waitFor(20));
  auto a = object<WhereAmI>(g, "a")->seen();
  auto b = object<WhereAmI>(g, "b")->seen();
  for (auto id : a) {
    EXPECT_EQ(id, a[0]);
  }
  for (auto id : b) {
    EXPECT_EQ(id, b[0]);
  }
  EXPECT_NE(a[0], b[0]);
  EXPECT_NE(a[0], std::this_thread::get_id());
  std::vector<int> want(20);
  for (int i = 0; i < 20; ++i) want[i] = i;
  EXPECT_EQ(sink()->ints(), want);
  std::vector<std::string> names;
  for (auto& s : g.groupStats()) names.push_back(s.name);
  EXPECT_THAT(names, ::testing::UnorderedElementsAre("default", "vision", "lidar"));
}

TEST_F(Threads, ANodeMovesBetweenGroupsWhileDataFlows) {
  add(g, "test/Feeder", "src");
  add(g, "test/WhereAmI", "a");
  add(g, "test/Collector", "sink");
  link(g, "src", "out", "a", "in");
  link(g, "a", "out", "sink", "in");
  g.start();
  for (int i = 0; i < 500; ++i) {
    src()->feed(i);
    if (i % 50 != 25) continue;
    ASSERT_TRUE(sink()->waitFor(i - 10));  // let `a` work in its current group first
    ASSERT_TRUE(g.setThreadGroup("a", i % 100 == 25 ? "moved" : "default"));
  }
  ASSERT_TRUE(sink()->waitFor(500));
  auto got = sink()->ints();
  for (int i = 0; i < 500; ++i) ASSERT_EQ(got[i], i) << "lost or reordered at " << i;
  auto seen = object<WhereAmI>(g, "a")->seen();
  std::set<std::thread::id> distinct(seen.begin(), seen.end());
  EXPECT_EQ(distinct.size(), 2u);
  EXPECT_EQ(g.describe().nodes[1].thread_group, "default");
}

TEST_F(Threads, PauseHoldsFiringResumeContinues) {
  add(g, "test/Feeder", "src");
  add(g, "test/Relay", "r");
  add(g, "test/Collector", "sink");
  link(g, "src", "out", "r", "in");
  link(g, "r", "out", "sink", "in");
  g.start();
  g.pause();
  EXPECT_TRUE(g.paused());
  src()->feed(1);
  ASSERT_TRUE(g.waitIdle(kWait));  // held: nothing fires
  EXPECT_EQ(sink()->size(), 0u);
  g.resume();
  ASSERT_TRUE(sink()->waitFor(1));
}

/** One run of the wave check; a step must never let a node of the same step's
 *  results fire (a race between groups taking their budgets used to). */
void stepWaves(NodeRegistry registry) {
  Graph g(std::move(registry));
  add(g, "test/Feeder", "src");
  add(g, "test/Relay", "r", "other");
  add(g, "test/Collector", "sink");
  link(g, "src", "out", "r", "in");
  link(g, "r", "out", "sink", "in");
  g.pause();
  g.start();
  auto* src = object<Feeder>(g, "src");
  auto* sink = object<Collector>(g, "sink");
  src->feed(1);
  src->feed(2);
  ASSERT_TRUE(g.waitIdle(kWait));
  g.step();  // src fires (1)
  ASSERT_EQ(sink->size(), 0u);
  g.step();  // r fires (1); src may now fire again in a later step
  ASSERT_EQ(sink->size(), 0u);
  g.step();  // sink gets 1, src sends 2
  ASSERT_EQ(sink->ints(), std::vector<int>{1});
  g.step();
  g.step();
  ASSERT_EQ(sink->ints(), (std::vector<int>{1, 2}));
  g.resume();
}

TEST_F(Threads, StepAdvancesOneWaveAtATime) {
  for (int i = 0; i < 100 && !HasFatalFailure(); ++i) stepWaves(g.registry());
}

/** One frame step on src -> a (vision) -> b (default) -> sink, src -> c (cloud) -> sink2:
 *  every node the frame reaches fires exactly once, the source once. */
void stepFrames(NodeRegistry registry) {
  Graph g(std::move(registry));
  ASSERT_TRUE(buildFromText(g, R"(
    nodes:
      - {name: src, type: test/Feeder}
      - {name: a, type: test/Relay, thread_group: vision}
      - {name: b, type: test/Relay}
      - {name: c, type: test/Relay, thread_group: cloud}
      - {name: sink, type: test/Collector}
      - {name: sink2, type: test/Collector, thread_group: cloud}
    connections: [{from: src/out, to: a/in}, {from: a/out, to: b/in}, {from: b/out, to: sink/in},
                  {from: src/out, to: c/in}, {from: c/out, to: sink2/in}])"));
  g.pause();
  g.start();
  auto* src = object<Feeder>(g, "src");
  for (int v = 1; v <= 3; ++v) src->feed(v);
  ASSERT_TRUE(g.waitIdle(kWait));
  for (int frame = 1; frame <= 2; ++frame) {
    ASSERT_TRUE(g.stepFrame());
    ASSERT_EQ(object<Collector>(g, "sink")->ints().back(), frame);  // all the way through
    ASSERT_EQ(object<Collector>(g, "sink2")->ints().back(), frame);
    for (const auto& n : g.nodeStats(0)) ASSERT_EQ(n.firings, std::uint64_t(frame)) << n.name;  // each once per frame
  }
  g.resume();
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(3));
}

TEST_F(Threads, AFrameStepTakesOneFrameThroughTheWholeGraph) {
  for (int i = 0; i < 100 && !HasFatalFailure(); ++i) stepFrames(g.registry());
  add(g, "test/Feeder", "src");
  g.start();
  EXPECT_EQ(g.stepFrame().message(), "the graph is running; pause it first");
}

TEST_F(Threads, OneWakeUpPerMessageCrossingIntoAnIdleGroup) {
  add(g, "test/Feeder", "src");
  add(g, "test/Collector", "sink", "far");
  link(g, "src", "out", "sink", "in");
  g.start();
  ASSERT_TRUE(g.waitIdle(kWait));  // both threads asleep: every message below must wake them
  for (int i = 0; i < 20; ++i) {
    src()->feed(i);
    ASSERT_TRUE(sink()->waitFor(i + 1));
    ASSERT_TRUE(g.waitIdle(kWait));
  }
  for (auto& s : g.groupStats()) {
    // feeding wakes `default` once per message; the message wakes `far` once;
    // the read acknowledgement finds `default` idle: at most one more.
    // feeding wakes `default` once per message and the message wakes `far`
    // once; the read acknowledgement goes back without waking anyone
    EXPECT_EQ(s.wakeups, 20u) << s.name;
  }
}

// A fast node in one group sends its parameter and an event to nodes of another group at every
// firing (a million times a second): that group's own data keeps flowing. Before, each value and
// each event was a mail of its own: the slower group ran mail only, its mailbox grew without bound
// and its nodes never fired again (the soak's "k2 got no data", one run in about twenty).
TEST_F(Threads, AFastNodesParameterAndEventsDoNotStopASlowerGroup) {
  ASSERT_TRUE(buildFromText(g, R"(
    nodes:
      - {name: tick, type: test/Ticker, thread_group: fast}
      - {name: fast, type: test/Gain, thread_group: fast}
      - {name: count, type: test/Counter, thread_group: fast}
      - {name: src, type: test/Feeder, thread_group: slow}
      - {name: gain, type: test/Gain, thread_group: slow}
      - {name: worker, type: test/SlowSlot, thread_group: slow}
      - {name: quiet, type: test/Counter, thread_group: slow}
      - {name: sink, type: test/Collector, thread_group: slow}
    connections: [{from: tick/out, to: fast/in}, {from: fast/out, to: count/in},
                  {from: src/out, to: gain/in}, {from: gain/out, to: sink/in}])"));
  ASSERT_TRUE(g.setInteractive("fast", "gain", true));
  ASSERT_TRUE(g.setInteractive("gain", "gain", true));
  link(g, "fast", "gain", "gain", "gain");  // sent at every firing of `fast`
  link(g, "fast", "processed", "worker", "work");  // an event at every firing, 50 us of work each
  link(g, "fast", "processed", "quiet", "disable");  // sets a state: never dropped
  std::mutex m;
  std::vector<std::string> warnings;
  setLogSink([&](LogLevel level, const std::string&, const std::string& text) {
    std::lock_guard<std::mutex> l(m);
    if (level == LogLevel::Warn) warnings.push_back(text);
  });
  g.start();
  // (a flood under way: it goes on as the frames are fed; 20,000 firings, as under TSan beside a
  // build it made 100,000 in no less than 10 s)
  ASSERT_TRUE(waitUntil([&] { return object<Counter>(g, "count")->count > 20000; }, 3 * kWait)) << "the fast group is slow";
  for (int i = 0; i < 20; ++i) src()->feed(i);
  const bool all = sink()->waitFor(20);
  const int fast = object<Counter>(g, "count")->count;
  g.stop();
  setLogSink(nullptr);
  EXPECT_TRUE(all) << "the slower group stopped: " << sink()->size() << " of 20 frames";
  EXPECT_GT(object<SlowSlot>(g, "worker")->runs, 0) << "of the events of " << fast << " firings";
  for (const auto& n : g.nodeStats()) {
    if (n.name == "quiet") EXPECT_FALSE(n.enabled);
  }
  std::lock_guard<std::mutex> l(m);
  ASSERT_EQ(warnings.size(), 1u) << "one warning, for 'work' ('disable' is never dropped)";
  EXPECT_THAT(warnings.front(), ::testing::HasSubstr("node 'worker' slot 'work' runs slower than node 'fast' fires 'processed'"));
}

TEST_F(Threads, StopJoinsAndCanRestart) {
  add(g, "test/Ticker", "tick");
  add(g, "test/Collector", "sink", "far");
  link(g, "tick", "out", "sink", "in");
  g.start();
  ASSERT_TRUE(sink()->waitFor(10));
  g.stop();
  const auto n = sink()->size();
  EXPECT_EQ(sink()->size(), n);  // nothing runs after stop returned
  g.start();
  ASSERT_TRUE(sink()->waitFor(n + 10));
  g.stop();
}

}  // namespace
