// Typed handles (ports.hpp): named once, checked at registration, used by index while
// running, and resolved again when an instance's interface changes.
#include <gmock/gmock.h>

#include "apex/core/ports.hpp"
#include "apex_test/test_nodes.hpp"
#include "graph_text.hpp"

using namespace apex_test;
using testing::ElementsAre;
using testing::HasSubstr;

namespace {

/** The Gain of docs/writing-nodes.md, with handles: out = in * gain; overflow fires past 1000. */
class HandleGain : public Node {
 public:
  static Manifest manifest() {
    return Manifest("multiplies")
        .input<int>("in")
        .output<int>("out")
        .param(param::range("gain", -100, 100, 1, 2))
        .trigger("overflow");
  }
  void process() override {
    const int out = *in_.get() * gain_.get();
    if (out > 1000) overflow_.fire();
    out_.publish(out);
  }

 private:
  Input<int> in_{this, "in"};
  Output<int> out_{this, "out"};
  Param<int> gain_{this, "gain"};
  Trigger overflow_{this, "overflow"};
};

/** Passes its input on by moving it (Input::take); notes whether the input still held it after. */
class TakingRelay : public Node {
 public:
  static Manifest manifest() { return Manifest().input<int>("in").output<int>("out"); }
  void process() override {
    const auto payload = in_.get().get();
    Message m = in_.take();
    moved_whole = m.as<int>().get() == payload;
    held_after = in_.has();
    out_.publishMessage(std::move(m));
  }
  std::atomic<bool> held_after{true}, moved_whole{false};

 private:
  Input<int> in_{this, "in"};
  Output<int> out_{this, "out"};
};

/** Has a times10 output only while `wide` is on; its handle throws while the port is gone. */
class Narrowing : public Node {
 public:
  static Manifest manifest() {
    return Manifest("an output that comes and goes")
        .input<int>("in")
        .output<int>("out")
        .param(param::boolean("wide", true).shapesInterface())
        .shapedBy([](const ParamValues& p, Manifest& m) {
          if (p.get<bool>("wide")) m.output<int>("times10");
          return Status::ok();
        });
  }
  void process() override {
    out_.publish(*in_.get());
    times10_.publish(*in_.get() * 10);
  }

 private:
  Input<int> in_{this, "in"};
  Output<int> out_{this, "out"};
  Output<int> times10_{this, "times10"};
};

std::string errorOf(const Graph& g, const std::string& node) {
  for (const auto& n : g.describe().nodes)
    if (n.name == node) return n.error;
  return "no node " + node;
}

template <class H>
class OneHandle : public Node {  // a node whose one handle is written wrongly
 public:
  static Manifest manifest() {
    return Manifest("wrong").input<int>("in").output<int>("out").param(param::range("gain", 0, 9, 1, 1)).trigger("t");
  }
  void process() override {}
  H h_{this, H::kName};
};
struct MisnamedInput : Input<int> {
  static constexpr const char* kName = "inn";
  using Input<int>::Input;
};
struct MistypedInput : Input<double> {
  static constexpr const char* kName = "in";
  using Input<double>::Input;
};
struct MistypedOutput : Output<std::string> {
  static constexpr const char* kName = "out";
  using Output<std::string>::Output;
};
struct MistypedParam : Param<double> {
  static constexpr const char* kName = "gain";
  using Param<double>::Param;
};
struct MisnamedTrigger : Trigger {
  static constexpr const char* kName = "done";
  using Trigger::Trigger;
};

TEST(Ports, AHandleReadsAndWritesByIndexWhileRunning) {
  NodeRegistry r = testRegistry();
  ASSERT_TRUE(r.add<HandleGain>("test/HandleGain"));
  Graph g(std::move(r));
  ASSERT_TRUE(buildFromText(g, R"(
    nodes:
      - {name: src, type: test/Feeder}
      - {name: gain, type: test/HandleGain, parameters: {gain: 3}}
      - {name: sink, type: test/Collector}
      - {name: overflows, type: test/Counter}
    connections: [{from: src/out, to: gain/in}, {from: gain/out, to: sink/in},
                  {from: gain/overflow, to: overflows/reset}])"));
  g.start();
  for (int v : {1, 2, 400}) object<Feeder>(g, "src")->feed(v);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(3));
  EXPECT_THAT(object<Collector>(g, "sink")->ints(), ElementsAre(3, 6, 1200));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(object<Counter>(g, "overflows")->resets, 1);
}

TEST(Ports, AHandleThatNamesNothingOrHasTheWrongTypeIsRefusedAtRegistration) {
  NodeRegistry r;
  auto st = r.add<OneHandle<MisnamedInput>>("test/A");
  EXPECT_THAT(st.message(), HasSubstr("node type 'test/A': Input<int> 'inn': manifest() declares no input 'inn' (inputs: in)"));
  st = r.add<OneHandle<MistypedInput>>("test/B");
  EXPECT_THAT(st.message(), HasSubstr("Input<double> 'in': input 'in' carries int: write Input<int>"));
  st = r.add<OneHandle<MistypedOutput>>("test/C");
  EXPECT_THAT(st.message(), HasSubstr("output 'out' carries int: write Output<int>"));
  st = r.add<OneHandle<MistypedParam>>("test/D");
  EXPECT_THAT(st.message(), HasSubstr("Param<double> 'gain': parameter 'gain' is a int range of int: write Param<int>"));
  st = r.add<OneHandle<MisnamedTrigger>>("test/E");
  EXPECT_THAT(st.message(), HasSubstr("Trigger 'done': manifest() declares no trigger 'done'"));
  EXPECT_TRUE(r.ids().empty());
}

TEST(Ports, HandlesFollowAnInterfaceThatChangesWhileRunning) {
  NodeRegistry r = testRegistry();
  ASSERT_TRUE(r.add<Narrowing>("test/Narrowing"));
  Graph g(std::move(r));
  add(g, "test/Feeder", "src");
  add(g, "test/Narrowing", "n");
  add(g, "test/Collector", "sink");
  link(g, "src", "out", "n", "in");
  link(g, "n", "out", "sink", "in");
  g.start();
  object<Feeder>(g, "src")->feed(1);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(1));
  ASSERT_TRUE(g.setParameter("n", "wide", "false"));  // the port goes: its handle now throws, named
  object<Feeder>(g, "src")->feed(2);
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_THAT(errorOf(g, "n"), HasSubstr("Output<int> 'times10' is not in this instance's interface"));
  ASSERT_TRUE(g.setParameter("n", "wide", "true"));  // back: the handle finds it again
  object<Feeder>(g, "src")->feed(3);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(3));
  EXPECT_THAT(object<Collector>(g, "sink")->ints(), ElementsAre(1, -999, 3));  // the failed firing sent Nothing
  EXPECT_EQ(errorOf(g, "n"), "");
}

}  // namespace

TEST(Ports, TakeMovesTheMessageOnAndLeavesTheInputEmptyForTheRestOfTheFiring) {
  NodeRegistry r = testRegistry();
  ASSERT_TRUE(r.add<TakingRelay>("test/TakingRelay"));
  Graph g(std::move(r));
  ASSERT_TRUE(buildFromText(g, R"(
    nodes:
      - {name: src, type: test/Feeder}
      - {name: relay, type: test/TakingRelay}
      - {name: sink, type: test/Collector}
    connections: [{from: src/out, to: relay/in}, {from: relay/out, to: sink/in}])"));
  g.start();
  for (int v : {7, 8}) object<Feeder>(g, "src")->feed(v);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(2));
  EXPECT_THAT(object<Collector>(g, "sink")->ints(), ElementsAre(7, 8));
  EXPECT_TRUE(object<TakingRelay>(g, "relay")->moved_whole) << "the same payload, not a copy";
  EXPECT_FALSE(object<TakingRelay>(g, "relay")->held_after) << "the input is Nothing once taken";
}
