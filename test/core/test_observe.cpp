// What hosts use to observe a graph: port taps, the revision counter,
// parameter values, the log sink; and adding a node with settings at once.
#include <gmock/gmock.h>

#include "apex_test/test_nodes.hpp"
#include "graph_text.hpp"

using namespace apex_test;
using ::testing::HasSubstr;

namespace {

TEST(Observe, ATapSeesEveryMessageOfAnOutputAndOfAParameterOutput) {
  Graph g(testRegistry());
  add(g, "test/Feeder", "src");
  add(g, "test/Gain", "gain");
  add(g, "test/Collector", "sink");
  link(g, "src", "out", "gain", "in");
  link(g, "gain", "out", "sink", "in");
  std::mutex m;
  std::vector<int> outs, gains;
  ASSERT_TRUE(g.setTap("gain", "out", [&](const Message& msg) {
    std::lock_guard<std::mutex> l(m);
    outs.push_back(*msg.as<int>());
  }));
  EXPECT_THAT(g.setTap("gain", "gain", [](const Message&) {}).message(), HasSubstr("no output or interactive parameter 'gain'"));
  ASSERT_TRUE(g.setInteractive("gain", "gain", true));
  ASSERT_TRUE(g.setTap("gain", "gain", [&](const Message& msg) {
    std::lock_guard<std::mutex> l(m);
    gains.push_back(*msg.as<int>());
  }));
  ASSERT_TRUE(g.setParameter("gain", "gain", "3"));
  g.start();
  for (int i = 1; i <= 3; ++i) object<Feeder>(g, "src")->feed(i);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(3));
  ASSERT_TRUE(g.waitIdle(kWait));
  ASSERT_TRUE(g.setTap("gain", "out", nullptr));  // removed: sees nothing more
  object<Feeder>(g, "src")->feed(4);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(4));
  ASSERT_TRUE(g.waitIdle(kWait));
  std::lock_guard<std::mutex> l(m);
  EXPECT_EQ(outs, (std::vector<int>{3, 6, 9}));
  EXPECT_GE(gains.size(), 4u);  // on the change and on every firing
  for (int v : gains) EXPECT_EQ(v, 3);
}

TEST(Observe, RevisionGrowsWithEditsAndWithChangesFromInside) {
  Graph g(testRegistry());
  const auto r0 = g.revision();
  add(g, "test/Feeder", "values");
  add(g, "test/Gain", "gain");
  EXPECT_GT(g.revision(), r0);
  ASSERT_TRUE(g.setInteractive("gain", "gain", true));
  link(g, "values", "out", "gain", "gain");
  g.start();
  ASSERT_TRUE(g.waitIdle(kWait));
  const auto r1 = g.revision();
  EXPECT_FALSE(g.connect("values", "out", "gain", "gain"));  // refused: no change
  EXPECT_EQ(g.revision(), r1);
  object<Feeder>(g, "values")->feed(7);  // a parameter changed by data, not by an edit
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_GT(g.revision(), r1);
  EXPECT_EQ(std::get<int>(g.parameterValue("gain", "gain").value()), 7);
  EXPECT_THAT(g.parameterValue("gain", "nope").message(), HasSubstr("no parameter 'nope'"));
}

TEST(Observe, AddingWithSettingsIsAllOrNothing) {
  Graph g(testRegistry());
  NodeDescription d;
  d.type = "test/Gain";
  d.name = "gain";
  d.parameters = {{"gain", "5"}};
  d.interactive = {"gain"};
  d.enabled = false;
  d.ui = "{x: 1}";
  ASSERT_EQ(g.addNode(d).value(), "gain");
  auto desc = g.describe().nodes.at(0);
  EXPECT_EQ(desc.parameters.at(0).second, "5");
  EXPECT_EQ(desc.interactive, std::vector<std::string>{"gain"});
  EXPECT_FALSE(desc.enabled);
  d.name = "bad";
  d.parameters = {{"gain", "500"}};
  auto r = g.addNode(d);
  EXPECT_THAT(r.message(), HasSubstr("out of range"));
  EXPECT_EQ(g.size(), 1u);  // nothing half-added
  d.type = "test/Nope";
  EXPECT_THAT(g.addNode(d).message(), HasSubstr("unknown node type 'test/Nope'"));
}

TEST(Observe, ErrorsGoToTheLogSinkOncePerChange) {
  std::mutex m;
  std::vector<std::string> lines;
  setLogSink([&](LogLevel level, const std::string& node, const std::string& text) {
    std::lock_guard<std::mutex> l(m);
    lines.push_back(std::to_string(static_cast<int>(level)) + " " + node + ": " + text);
  });
  {
    Graph g(testRegistry());
    ASSERT_TRUE(buildFromText(g, R"(
      nodes:
        - {name: src, type: test/Feeder}
        - {name: t, type: test/Thrower, parameters: {throw_on: 1}}
        - {name: sink, type: test/Collector}
      connections: [{from: src/out, to: t/in}, {from: t/out, to: sink/in}])"));
    g.start();
    for (int v : {1, 1, 1, 2}) object<Feeder>(g, "src")->feed(v);
    ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(4));
    ASSERT_TRUE(g.waitIdle(kWait));
  }
  setLogSink(nullptr);
  std::lock_guard<std::mutex> l(m);
  ASSERT_EQ(lines.size(), 2u);  // the error once, then the recovery
  EXPECT_THAT(lines[0], HasSubstr("3 t: node 't' (test/Thrower) threw: bad value 1"));
  EXPECT_THAT(lines[1], HasSubstr("1 t: recovered"));
}

TEST(Observe, AnErrorThatChangesEveryFiringIsLoggedOnceButShownNewest) {
  std::mutex m;
  std::vector<std::string> lines;
  setLogSink([&](LogLevel, const std::string&, const std::string& text) {
    std::lock_guard<std::mutex> l(m);
    lines.push_back(text);
  });
  {
    Graph g(testRegistry());
    add(g, "test/Feeder", "src");
    add(g, "test/Thrower", "t");
    link(g, "src", "out", "t", "in");
    ASSERT_TRUE(g.setParameter("t", "throw_always", "true"));
    g.start();
    for (int v = 1; v <= 50; ++v) {
      object<Feeder>(g, "src")->feed(v);
      ASSERT_TRUE(g.waitIdle(kWait));
    }
    for (const auto& n : g.nodeStats())  // the state is the newest failure
      if (n.name == "t") {
        EXPECT_THAT(n.error, HasSubstr("bad value 50"));
      }
  }
  setLogSink(nullptr);
  std::lock_guard<std::mutex> l(m);
  ASSERT_EQ(lines.size(), 1u) << "a failure at every firing floods the log";
  EXPECT_THAT(lines[0], HasSubstr("bad value 1"));
}

}  // namespace

namespace {

/** A source at a rate, the way a clock node is written: setup() starts it. */
struct Tick : Node {
  static Manifest manifest() { return Manifest().output<int>("out").driven().param(param::real("period", 0.001)); }
  void setup() override {
    ++setups;
    notifyNewData();
  }
  void process() override {
    publish("out", n++);
    notifyAfter(param<double>("period"));
  }
  int n = 0;
  std::atomic<int> setups{0};
};

TEST(Observe, RatesCountFramesAndFiringsThatOnlyPassNothingAreCountedApart) {
  Graph g(testRegistry());
  add(g, "test/Feeder", "src");
  add(g, "test/OptionalSum", "sum");
  add(g, "test/Collector", "sink");
  link(g, "src", "out", "sum", "a");
  link(g, "sum", "sum", "sink", "in");
  g.start();
  for (int v = 1; v <= 3; ++v) object<Feeder>(g, "src")->feed(v);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(3));
  ASSERT_TRUE(g.waitIdle(kWait));
  object<Feeder>(g, "src")->notifyNewData();  // nothing queued: the source sends Nothing, and so does the chain
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(4));
  ASSERT_TRUE(g.waitIdle(kWait));
  for (const auto& n : g.nodeStats(0)) {
    EXPECT_EQ(n.firings, 3u) << n.name;
    EXPECT_EQ(n.nothing_firings, 1u) << n.name;
  }
}

TEST(Observe, EachOutputCountsTheMessagesItSentNotTheNothingOfAFailedFiring) {
  // the rate the panel writes on a link: what its output sent, over time
  Graph g(testRegistry());
  add(g, "test/Feeder", "src");
  add(g, "test/Thrower", "t");
  add(g, "test/Collector", "sink");
  ASSERT_EQ(g.setParameter("t", "throw_on", "2").value(), "2");
  link(g, "src", "out", "t", "in");
  link(g, "t", "out", "sink", "in");
  g.start();
  for (int v = 1; v <= 4; ++v) object<Feeder>(g, "src")->feed(v);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(4));
  ASSERT_TRUE(g.waitIdle(kWait));
  using Sent = std::vector<std::pair<std::string, std::uint64_t>>;
  const auto sent = [](const NodeStats& s) {
    Sent out;
    for (const auto& o : s.outputs) out.emplace_back(o.name, o.sent);
    return out;
  };
  const auto stats = g.nodeStats(0);
  EXPECT_EQ(sent(stats[0]), (Sent{{"out", 4}}));
  EXPECT_EQ(sent(stats[1]), (Sent{{"out", 3}})) << "the failed firing sent Nothing";
  EXPECT_EQ(sent(stats[2]), Sent{}) << "a sink has no outputs";
}

TEST(Timers, ASourceAtARateUsesTheGroupsTimerAndSetup) {
  Graph g(testRegistry());
  ASSERT_TRUE(g.registry().add<Tick>("test/Tick"));
  add(g, "test/Tick", "tick");
  add(g, "test/Collector", "sink");
  link(g, "tick", "out", "sink", "in");
  g.start();
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(20));
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GE(elapsed, 0.019);  // 20 ticks, 1 ms apart, never faster
  EXPECT_EQ(object<Tick>(g, "tick")->setups.load(), 1);
  ASSERT_TRUE(g.setThreadGroup("tick", "other"));  // its timer follows it
  const auto n = object<Collector>(g, "sink")->size();
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(n + 20));
  ASSERT_TRUE(g.removeNode("tick"));  // a pending timer for a removed node does nothing
  EXPECT_TRUE(g.waitIdle(kWait));
}

}  // namespace
