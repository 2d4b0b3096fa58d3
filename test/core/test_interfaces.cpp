// Interfaces per instance (Manifest::shapedBy): ports that follow parameters,
// changed as live edits while data flows, saved and loaded.
#include <gmock/gmock.h>

#include "apex/core/graph_file.hpp"
#include "apex_test/test_nodes.hpp"
#include "graph_text.hpp"

using namespace apex_test;
using testing::ElementsAre;

namespace {

std::string indexed(const std::string& base, int i) { return base + "_" + std::to_string(i); }

/** Copies its input to `outputs` outputs out_0, out_1, ...; `kind: text` makes them strings. */
class Fan : public Node {
 public:
  static Manifest manifest() {
    return Manifest("one input to N outputs")
        .input<int>("in")
        .param(param::range("outputs", 0, 16, 1, 2).shapesInterface())
        .param(param::options("kind", {"int", "text"}, "int").shapesInterface())
        .param(param::range("gain", 1, 10, 1, 1))
        .shapedBy([](const ParamValues& p, Manifest& m) {
          if (p.get<std::string>("kind") == "text" && p.get<int>("outputs") > 8) return Status::error("at most 8 text outputs");
          for (int i = 0; i < p.get<int>("outputs"); ++i) {
            if (p.get<std::string>("kind") == "text") m.output<std::string>(indexed("out", i));
            else m.output<int>(indexed("out", i));
          }
          return Status::ok();
        });
  }
  void process() override {
    const int v = *input<int>("in") * param<int>("gain");
    for (const auto& out : interface().outputs) {
      if (out.type == typeOf<std::string>()) publish(out.name, std::to_string(v));
      else publish(out.name, v);
    }
  }
};

/** Sums `inputs` optional inputs in_0, in_1, ...: a join whose width is a parameter. */
class Merge : public Node {
 public:
  static Manifest manifest() {
    return Manifest("sums N inputs")
        .output<int>("sum")
        .param(param::range("inputs", 1, 16, 1, 2).shapesInterface())
        .shapedBy([](const ParamValues& p, Manifest& m) {
          for (int i = 0; i < p.get<int>("inputs"); ++i) m.input<int>(indexed("in", i));
          return Status::ok();
        });
  }
  void process() override {
    int s = 0;
    for (const auto& in : interface().inputs) s += *input<int>(in.name);
    publish("sum", s);
  }
};

/** An interface function that breaks the rules it is given. */
class Rogue : public Node {
 public:
  static Manifest manifest() {
    return Manifest("makes bad interfaces")
        .param(param::options("mode", {"fine", "clash", "drop_builtin", "throw"}, "fine").shapesInterface())
        .shapedBy([](const ParamValues& p, Manifest& m) {
          const auto& mode = p.get<std::string>("mode");
          if (mode == "clash") m.output<int>("x").output<int>("x");
          if (mode == "drop_builtin") m.slots.clear();
          if (mode == "throw") throw std::runtime_error("no bag here");
          return Status::ok();
        });
  }
  void process() override {}
};

NodeRegistry registry() {
  NodeRegistry r = testRegistry();
  EXPECT_TRUE(r.add<Fan>("test/Fan"));
  EXPECT_TRUE(r.add<Merge>("test/Merge"));
  EXPECT_TRUE(r.add<Rogue>("test/Rogue"));
  return r;
}

std::vector<std::string> outputs(const Graph& g, const std::string& node) {
  std::vector<std::string> out;
  for (const auto& p : g.nodeInterface(node)->outputs) out.push_back(p.name);
  return out;
}

std::vector<std::string> connections(const Graph& g) {
  std::vector<std::string> out;
  for (const auto& c : g.describe().connections)
    out.push_back(c.from_node + "/" + c.from_port + ">" + c.to_node + "/" + c.to_port);
  return out;
}

void set(Graph& g, const std::string& node, const std::string& param, const std::string& value) {
  auto r = g.setParameter(node, param, value);
  ASSERT_TRUE(r) << r.message();
}

TEST(Interfaces, ANewNodeHasThePortsOfItsDefaultParameters) {
  Graph g(registry());
  add(g, "test/Fan", "fan");
  EXPECT_THAT(outputs(g, "fan"), ElementsAre("out_0", "out_1"));
  EXPECT_THAT(g.nodeType("fan")->manifest->outputs, testing::IsEmpty());  // the type stays as declared
  const auto d = g.describe();
  ASSERT_TRUE(d.nodes[0].interface);
  EXPECT_EQ(d.nodes[0].interface->outputs.size(), 2u);
}

TEST(Interfaces, VanishedPortsLoseTheirConnectionsWhileTheRestFlows) {
  Graph g(registry());
  add(g, "test/Feeder", "src");
  add(g, "test/Fan", "fan");
  set(g, "fan", "outputs", "3");
  for (int i = 0; i < 3; ++i) {
    add(g, "test/Collector", indexed("sink", i));
    link(g, "fan", indexed("out", i), indexed("sink", i), "in");
  }
  link(g, "src", "out", "fan", "in");
  g.start();
  object<Feeder>(g, "src")->feed(1);
  ASSERT_TRUE(object<Collector>(g, "sink_2")->waitFor(1));

  set(g, "fan", "outputs", "1");  // while running
  EXPECT_THAT(outputs(g, "fan"), ElementsAre("out_0"));
  EXPECT_THAT(connections(g), ElementsAre("src/out>fan/in", "fan/out_0>sink_0/in"));
  object<Feeder>(g, "src")->feed(2);
  object<Feeder>(g, "src")->feed(3);
  ASSERT_TRUE(object<Collector>(g, "sink_0")->waitFor(3));  // nothing stalls
  EXPECT_THAT(object<Collector>(g, "sink_0")->ints(), ElementsAre(1, 2, 3));

  set(g, "fan", "outputs", "3");  // undo: the ports come back, the connections are made again
  link(g, "fan", "out_2", "sink_2", "in");
  object<Feeder>(g, "src")->feed(4);
  ASSERT_TRUE(object<Collector>(g, "sink_2")->waitFor(2));
  EXPECT_EQ(object<Collector>(g, "sink_2")->ints().back(), 4);
  EXPECT_TRUE(g.waitIdle(kWait));
}

TEST(Interfaces, ARetypedPortKeepsTheConnectionsItsNewTypeFits) {
  Graph g(registry());
  add(g, "test/Fan", "fan");
  add(g, "test/Relay", "any");  // takes anything
  add(g, "test/Gain", "ints");  // takes int
  link(g, "fan", "out_0", "any", "in");
  link(g, "fan", "out_1", "ints", "in");
  set(g, "fan", "kind", "text");
  EXPECT_THAT(connections(g), ElementsAre("fan/out_0>any/in"));
  EXPECT_EQ(g.nodeInterface("fan")->outputs[0].type, typeOf<std::string>());
}

TEST(Interfaces, AJoinCanNarrowWhileFramesFlow) {
  Graph g(registry());
  ASSERT_TRUE(buildFromText(g, R"(
    nodes:
      - {name: src, type: test/Feeder}
      - {name: slow_path, type: test/Relay}
      - {name: merge, type: test/Merge, parameters: {inputs: 3}}
      - {name: sink, type: test/Collector}
    connections: [{from: src/out, to: merge/in_0},
                  {from: src/out, to: slow_path/in}, {from: slow_path/out, to: merge/in_1},
                  {from: src/out, to: merge/in_2}, {from: merge/sum, to: sink/in}])"));
  g.start();
  for (int v = 1; v <= 3; ++v) object<Feeder>(g, "src")->feed(v);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(3));
  EXPECT_THAT(object<Collector>(g, "sink")->ints(), ElementsAre(3, 6, 9));
  set(g, "merge", "inputs", "2");  // in_2 goes, with its connection; the join never pairs two frames
  for (int v = 4; v <= 6; ++v) object<Feeder>(g, "src")->feed(v);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(6));
  EXPECT_THAT(object<Collector>(g, "sink")->ints(), ElementsAre(3, 6, 9, 8, 10, 12));
}

TEST(Interfaces, ParametersOfKeptPortsAndTheirValuesStay) {
  Graph g(registry());
  add(g, "test/Fan", "fan");
  set(g, "fan", "gain", "7");
  set(g, "fan", "outputs", "5");
  EXPECT_EQ(std::get<int>(g.parameterValue("fan", "gain").value()), 7);
  EXPECT_EQ(std::get<int>(g.parameterValue("fan", "outputs").value()), 5);
}

TEST(Interfaces, ARefusedInterfaceRefusesTheParameterAndChangesNothing) {
  Graph g(registry());
  add(g, "test/Fan", "fan");
  set(g, "fan", "outputs", "12");
  auto r = g.setParameter("fan", "kind", "text");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.message(), "node 'fan' (test/Fan) cannot make its ports for kind = text: at most 8 text outputs");
  EXPECT_EQ(std::get<std::string>(g.parameterValue("fan", "kind").value()), "int");
  EXPECT_EQ(outputs(g, "fan").size(), 12u);

  add(g, "test/Rogue", "rogue");
  EXPECT_THAT(g.setParameter("rogue", "mode", "clash").message(), testing::HasSubstr("two outputs are named 'x'"));
  EXPECT_THAT(g.setParameter("rogue", "mode", "drop_builtin").message(),
              testing::HasSubstr("removed or moved the built-in slot 'enable'"));
  EXPECT_THAT(g.setParameter("rogue", "mode", "throw").message(), testing::HasSubstr("no bag here"));
  EXPECT_EQ(std::get<std::string>(g.parameterValue("rogue", "mode").value()), "fine");
}

TEST(Interfaces, AParameterThatDecidesThePortsCannotHavePorts) {
  Graph g(registry());
  add(g, "test/Fan", "fan");
  auto st = g.setInteractive("fan", "outputs", true);
  ASSERT_FALSE(st);
  EXPECT_EQ(st.message(),
            "parameter 'outputs' of node 'fan' decides the node's ports: it is set by edits only and cannot have ports");
  EXPECT_TRUE(g.setInteractive("fan", "gain", true));
}

TEST(Interfaces, ASavedGraphLoadsBackWithTheSamePortsAndConnections) {
  Graph g(registry());
  add(g, "test/Fan", "fan");
  add(g, "test/Merge", "merge");
  set(g, "fan", "outputs", "4");
  set(g, "merge", "inputs", "4");
  for (int i = 0; i < 4; ++i) link(g, "fan", indexed("out", i), "merge", indexed("in", 3 - i));
  const std::string text = formatGraphText(g.describe());

  Graph h(registry());
  auto parsed = parseGraphText(text);
  ASSERT_TRUE(parsed) << parsed.message();
  auto loaded = h.load(parsed.value());
  ASSERT_TRUE(loaded) << loaded.message();
  EXPECT_EQ(connections(h), connections(g));
  EXPECT_EQ(outputs(h, "fan"), outputs(g, "fan"));
  EXPECT_EQ(formatGraphText(h.describe()), text);
}

}  // namespace
