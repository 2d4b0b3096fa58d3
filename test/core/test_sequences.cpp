// Sequences and the rules an optimisation loop relies on: the end-of-sequence token travels in
// step with the frames, events leave after the messages of the same firing or slot, a slot may
// publish, a node sees the parameters its outputs feed, and reportError keeps what was sent.
#include <gmock/gmock.h>

#include <condition_variable>
#include <mutex>
#include <thread>

#include "apex_test/test_nodes.hpp"
#include "graph_text.hpp"

using namespace apex_test;
using ::testing::HasSubstr;

namespace {

/** Sums its input; at the end of a sequence sends the sum and starts again. */
class Summer : public Node {
 public:
  static Manifest manifest() {
    return Manifest("sums a sequence").input<int>("in").output<int>("sum").slot("announce", &Summer::announce);
  }
  void process() override { sum_ += *input<int>("in"); }
  void endOfSequence() override {
    publish("sum", sum_);
    sum_ = 0;
  }
  void announce() { publish("sum", -1); }  // from a slot

 private:
  int sum_ = 0;
};

/** Publishes the values of a parameter its output feeds, and a value, from a slot. */
class Setter : public Node {
 public:
  static Manifest manifest() {
    return Manifest("sets a parameter")
        .output<int>("value")
        .slot("send", &Setter::send)
        .trigger("sent")
        .param(param::integer("to", 7))
        .driven();  // fires only when told: its slot sends
  }
  void process() override {}
  void send() {
    targets = parameterTargets("value");
    publish("value", param<int>("to"));
    trigger("sent");
  }
  std::vector<ParamTarget> targets;
};

/** Per input: sends it on, fires `sent`, then works a while (the event must still wait). */
class SlowSetter : public Node {
 public:
  static Manifest manifest() { return Manifest("sets a parameter slowly").input<int>("in").output<int>("value").trigger("sent"); }
  void process() override {
    publish("value", *input<int>("in"));
    trigger("sent");
    std::this_thread::sleep_for(20ms);  // the rest of a long process(): its messages leave only after it
  }
};

/** Reports the gain it holds when its slot runs. */
class GainProbe : public Node {
 public:
  static Manifest manifest() {
    return Manifest("records its gain on an event")
        .slot("probe", &GainProbe::probe)
        .param(param::range("gain", 0, 100, 1, 1).makeInteractive());
  }
  void process() override {}
  void probe() { seen.push_back(param<int>("gain")); }
  std::vector<int> seen;
};

/** Its slot holds its group's thread until the test lets it go: a group busy for a while. */
class Stall : public Node {
 public:
  static Manifest manifest() { return Manifest("holds its thread").slot("hold", &Stall::hold); }
  void process() override {}
  void hold() {
    std::unique_lock<std::mutex> lock(m);
    held = true;
    cv.wait(lock, [this] { return go.load(); });
  }
  void letGo() {
    std::lock_guard<std::mutex> lock(m);
    go = true;
    cv.notify_all();
  }
  std::atomic<bool> held{false}, go{false};
  std::mutex m;
  std::condition_variable cv;
};

/** Reports an error and still publishes. */
class Reporter : public Node {
 public:
  static Manifest manifest() { return Manifest("reports").input<int>("in").output<int>("out"); }
  void process() override {
    const int v = *input<int>("in");
    if (v < 0) reportError("negative input " + std::to_string(v));
    publish("out", v);
  }
};

NodeRegistry registry() {
  NodeRegistry r = testRegistry();
  EXPECT_TRUE(r.add<Summer>("test/Summer"));
  EXPECT_TRUE(r.add<Setter>("test/Setter"));
  EXPECT_TRUE(r.add<SlowSetter>("test/SlowSetter"));
  EXPECT_TRUE(r.add<GainProbe>("test/GainProbe"));
  EXPECT_TRUE(r.add<Reporter>("test/Reporter"));
  EXPECT_TRUE(r.add<Stall>("test/Stall"));
  return r;
}

TEST(Sequences, TheEndTravelsInStepThroughAChainAndADisabledNode) {
  Graph g(registry());
  ASSERT_TRUE(buildFromText(g, R"(
    nodes:
      - {name: seq, type: test/Sequence, parameters: {frames: 50}}
      - {name: a, type: test/Relay, thread_group: one}
      - {name: b, type: test/Relay, thread_group: two}  # disabled below: passes the end on all the same
      - {name: sum, type: test/Summer, thread_group: three}
      - {name: sums, type: test/Collector}
    connections: [{from: seq/out, to: a/in}, {from: a/out, to: b/in}, {from: b/out, to: sum/in},
                  {from: sum/sum, to: sums/in}])"));
  g.start();
  ASSERT_TRUE(g.fireSlot("seq", "restart"));
  ASSERT_TRUE(object<Collector>(g, "sums")->waitFor(50 + 1));  // Nothing per frame, then the sum
  auto got = object<Collector>(g, "sums")->ints();
  EXPECT_EQ(got.back(), 49 * 50 / 2) << "the end arrived before the last frames";
  ASSERT_TRUE(g.setEnabled("b", false));
  ASSERT_TRUE(g.fireSlot("seq", "restart"));
  ASSERT_TRUE(object<Collector>(g, "sums")->waitFor(2 * 51));
  EXPECT_EQ(object<Collector>(g, "sums")->ints().back(), 0) << "a disabled node sends Nothing, and the end";
  EXPECT_TRUE(g.waitIdle(kWait));
}

TEST(Sequences, NeitherNothingNorTheEndOfASequenceSetsAParameter) {
  // frames into a parameter: each sets it; the end of the sequence is no value and no error
  Graph g(registry());
  add(g, "test/Sequence", "seq");
  add(g, "test/GainProbe", "probe", "two");
  link(g, "seq", "out", "probe", "gain");
  ASSERT_TRUE(g.setParameter("seq", "frames", "5"));
  g.start();
  ASSERT_TRUE(g.fireSlot("seq", "restart"));
  ASSERT_TRUE(waitUntil([&] { return std::get<int>(g.parameterValue("probe", "gain").value()) == 4; }));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(std::get<int>(g.parameterValue("probe", "gain").value()), 4);
  EXPECT_EQ(g.nodeStats()[1].error, "");
}

TEST(Sequences, EventsLeaveAfterTheMessagesOfTheirFiringAndSlot) {
  // The setter's value reaches the probe's gain (another group) before its event reaches the probe.
  Graph g(registry());
  add(g, "test/Setter", "set", "one");
  add(g, "test/GainProbe", "probe", "two");
  link(g, "set", "value", "probe", "gain");
  link(g, "set", "sent", "probe", "probe");
  g.start();
  for (int v = 10; v < 60; ++v) {
    ASSERT_TRUE(g.setParameter("set", "to", std::to_string(v)));
    ASSERT_TRUE(g.fireSlot("set", "send"));
    ASSERT_TRUE(g.waitIdle(kWait));
  }
  const auto& seen = object<GainProbe>(g, "probe")->seen;
  ASSERT_EQ(seen.size(), 50u);
  for (int i = 0; i < 50; ++i) EXPECT_EQ(seen[i], 10 + i) << "the event overtook the value";
}

TEST(Sequences, EventsFromProcessLeaveAfterItsMessagesHoweverLongItTakes) {
  Graph g(registry());
  ASSERT_TRUE(buildFromText(g, R"(
    nodes:
      - {name: src, type: test/Feeder}
      - {name: set, type: test/SlowSetter, thread_group: one}
      - {name: probe, type: test/GainProbe, thread_group: two, interactive: [gain]}
    connections: [{from: src/out, to: set/in}, {from: set/value, to: probe/gain}, {from: set/sent, to: probe/probe}])"));
  g.start();
  for (int v = 10; v < 15; ++v) object<Feeder>(g, "src")->feed(v);
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(object<GainProbe>(g, "probe")->seen, (std::vector<int>{10, 11, 12, 13, 14}));
}

TEST(Sequences, ASlotPublishesAndSeesTheParametersItFeeds) {
  Graph g(registry());
  add(g, "test/Setter", "set");
  add(g, "test/GainProbe", "probe");
  link(g, "set", "value", "probe", "gain");
  ASSERT_TRUE(g.setParameter("probe", "gain", "42"));
  g.start();
  ASSERT_TRUE(g.waitIdle(kWait));
  ASSERT_TRUE(g.fireSlot("set", "send"));
  ASSERT_TRUE(g.waitIdle(kWait));
  const auto& targets = object<Setter>(g, "set")->targets;
  ASSERT_EQ(targets.size(), 1u);
  EXPECT_EQ(targets[0].node, "probe");
  EXPECT_EQ(targets[0].spec.name, "gain");
  EXPECT_EQ(targets[0].spec.max, 100);
  EXPECT_EQ(std::get<int>(targets[0].value), 42);
  EXPECT_EQ(std::get<int>(g.parameterValue("probe", "gain").value()), 7) << "the slot's message did not arrive";
}

TEST(Sequences, ASlotSetsAParameterWhoseLastValueIsStillInTheMailOfABusyGroup) {
  // The Optimizer's run ends by giving the tuned parameters their old values back; apply_best,
  // right after, sends the best ones. On a loaded machine the receivers' group had not applied
  // the old values yet, and the best ones were refused for good (clean CI: "apply_best did not
  // reach the tuned parameters"). A value for a parameter is a setting: it goes behind the last.
  Graph g(registry());
  add(g, "test/Setter", "set", "one");
  add(g, "test/Stall", "marker", "one");  // let go at once: its slot runs after what group one was asked before
  add(g, "test/GainProbe", "probe", "two");
  add(g, "test/Stall", "stall", "two");
  link(g, "set", "value", "probe", "gain");
  g.start();
  auto* stall = object<Stall>(g, "stall");
  auto* marker = object<Stall>(g, "marker");
  marker->letGo();
  ASSERT_TRUE(g.fireSlot("stall", "hold"));
  ASSERT_TRUE(waitUntil([&] { return stall->held.load(); }));  // group two applies nothing until let go
  ASSERT_TRUE(g.setParameter("set", "to", "5"));
  ASSERT_TRUE(g.fireSlot("set", "send"));
  ASSERT_TRUE(g.setParameter("set", "to", "9"));
  ASSERT_TRUE(g.fireSlot("set", "send"));
  ASSERT_TRUE(g.fireSlot("marker", "hold"));
  ASSERT_TRUE(waitUntil([&] { return marker->held.load(); }));  // group one has made both sends
  stall->letGo();
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(std::get<int>(g.parameterValue("probe", "gain").value()), 9) << "the newer value was not sent";
  for (const auto& s : g.nodeStats()) EXPECT_EQ(s.error, "") << s.name;
  ASSERT_TRUE(g.setParameter("set", "to", "11"));  // and the edge is as before: counted, read
  ASSERT_TRUE(g.fireSlot("set", "send"));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(std::get<int>(g.parameterValue("probe", "gain").value()), 11);
  for (const auto& s : g.nodeStats()) EXPECT_EQ(s.error, "") << s.name;
}

TEST(Sequences, ASlotThatCannotSendBecauseTheReceiverHoldsTheLastMessageSaysSo) {
  Graph g(registry());
  add(g, "test/Summer", "sum", "one");
  add(g, "test/Collector", "out", "two");
  add(g, "test/Feeder", "src");
  link(g, "src", "out", "sum", "in");
  link(g, "sum", "sum", "out", "in");
  g.start();
  g.pause();  // slots still run, nothing fires: nobody reads what the first one sends
  ASSERT_TRUE(g.fireSlot("sum", "announce"));
  ASSERT_TRUE(g.fireSlot("sum", "announce"));
  EXPECT_TRUE(waitUntil([&] { return !g.nodeStats()[0].error.empty(); }));
  EXPECT_THAT(g.nodeStats()[0].error, HasSubstr("slot 'announce' published on output 'sum' while 'out' had not read"));
  g.resume();
  ASSERT_TRUE(object<Collector>(g, "out")->waitFor(1));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(object<Collector>(g, "out")->ints(), std::vector<int>{-1});
  object<Feeder>(g, "src")->feed(1);  // the firing rule holds: the node fires again once read
  ASSERT_TRUE(object<Collector>(g, "out")->waitFor(2));
}

TEST(Sequences, AReportedErrorStaysWhileTheOutputsGoOut) {
  Graph g(registry());
  add(g, "test/Feeder", "src");
  add(g, "test/Reporter", "r");
  add(g, "test/Collector", "out");
  link(g, "src", "out", "r", "in");
  link(g, "r", "out", "out", "in");
  g.start();
  object<Feeder>(g, "src")->feed(-3);
  ASSERT_TRUE(object<Collector>(g, "out")->waitFor(1));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(object<Collector>(g, "out")->ints(), std::vector<int>{-3});
  EXPECT_THAT(g.nodeStats()[1].error, HasSubstr("node 'r' (test/Reporter): negative input -3"));
  object<Feeder>(g, "src")->feed(4);
  ASSERT_TRUE(object<Collector>(g, "out")->waitFor(2));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(g.nodeStats()[1].error, "");
}

}  // namespace
