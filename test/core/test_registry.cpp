// Node types: one registration per type, manifests listed without instances,
// the function adapter, and refused registrations.
#include <gmock/gmock.h>

#include "apex/core/function_node.hpp"
#include "apex/core/node_names.hpp"
#include "apex_test/test_nodes.hpp"
#include "graph_text.hpp"

using namespace apex_test;
using ::testing::HasSubstr;

namespace {

int plus(int a, int b) { return a + b; }

class Doubler : public apex::Node {
 public:
  static apex::Manifest manifest() { return apex::Manifest("Doubles an int").input<int>("in").output<int>("out"); }
  void process() override { publish("out", *input<int>("in") * 2); }
};

}  // namespace

APEX_REGISTER_NODE(Doubler, "test/Doubler");

TEST(Registry, OneLineRegistersATypeForThisProgramAndForItsLibrary) {
  const auto type = apex::NodeRegistry::global().find("test/Doubler");
  ASSERT_NE(type, nullptr);
  EXPECT_EQ(type->manifest->description, "Doubles an int");
  // A plugin library hands the host its module's list (APEX_NODE_LIBRARY): the same type.
  EXPECT_EQ(apex::detail::moduleTypes().find("test/Doubler"), type);
  EXPECT_EQ(apex::detail::moduleTypes().ids(), std::vector<std::string>{"test/Doubler"});
  apex::Graph graph;  // starts from the process-wide registry
  EXPECT_TRUE(graph.addNode("test/Doubler", "d"));
  // A second registration of the id is refused (and reported on stderr).
  EXPECT_FALSE(apex::detail::registerNode<Doubler>("test/Doubler"));
}

TEST(Registry, AnUnloadedLibrarysTypesLeaveTheProcessWideRegistry) {
  // Their factories are the library's code: left behind, a graph made from the registry after
  // the library was unloaded, or the registry's own destruction at exit, would call into it.
  {
    apex::detail::ModuleTypes library;  // what a plugin library holds, gone when it is unloaded
    ASSERT_TRUE(library.types.add<Doubler>("test/Unloaded"));
    ASSERT_TRUE(apex::NodeRegistry::global().add(library.types.find("test/Unloaded")));
    ASSERT_TRUE(library.types.add<Doubler>("test/Doubler"));  // an id another module owns
  }
  EXPECT_EQ(apex::NodeRegistry::global().find("test/Unloaded"), nullptr);
  EXPECT_NE(apex::NodeRegistry::global().find("test/Doubler"), nullptr);  // not this library's entry
}

TEST(Registry, ListsAWholeInterfaceWithoutCreatingANode) {
  NodeRegistry r = testRegistry();
  auto type = r.find("test/Counter");
  ASSERT_TRUE(type);
  const Manifest& m = *type->manifest;
  ASSERT_EQ(m.inputs.size(), 1u);
  EXPECT_EQ(m.inputs[0].type, typeOf<Any>());
  ASSERT_EQ(m.params.size(), 1u);
  EXPECT_EQ(m.params[0].name, "every");
  // built-in events come first, then the type's own
  ASSERT_EQ(m.slots.size(), 3u);
  EXPECT_EQ(m.slots[0].name, "enable");
  EXPECT_EQ(m.slots[1].name, "disable");
  EXPECT_EQ(m.slots[2].name, "reset");
  ASSERT_EQ(m.triggers.size(), 2u);
  EXPECT_EQ(m.triggers[0].name, "processed");
  EXPECT_EQ(m.triggers[1].name, "every_n");
}

TEST(Registry, RefusesADuplicateId) {
  NodeRegistry r;
  ASSERT_TRUE(r.add<Relay>("test/Relay"));
  auto st = r.add<Relay>("test/Relay");
  ASSERT_FALSE(st);
  EXPECT_THAT(st.message(), HasSubstr("'test/Relay' is already registered"));
}

TEST(Registry, RefusesABadIdOrClashingNames) {
  NodeRegistry r;
  EXPECT_THAT(r.add<Relay>("Relay").message(), HasSubstr("must look like 'package/Name'"));
  auto clash = r.add("test/Clash", Manifest().input<int>("x").param(param::integer("x", 0)),
                     [] { return std::unique_ptr<Node>(new Relay()); });
  EXPECT_THAT(clash.message(), HasSubstr("parameter 'x' has the name of another port"));
  auto builtin = r.add("test/Builtin", Manifest().trigger("processed"), [] { return std::unique_ptr<Node>(new Relay()); });
  EXPECT_THAT(builtin.message(), HasSubstr("'processed'"));
  auto bad_default = r.add("test/BadDefault", Manifest().param(param::range("block", 3, 99, 2, 10)),
                           [] { return std::unique_ptr<Node>(new Relay()); });
  EXPECT_THAT(bad_default.message(), HasSubstr("default value"));
  EXPECT_THAT(bad_default.message(), HasSubstr("not on the step"));
}

TEST(Registry, UnknownTypeSaysWhereTheKnownOnesAreListed) {
  Graph g(testRegistry());
  auto r = g.addNode("test/Nope");
  ASSERT_FALSE(r);
  EXPECT_THAT(r.message(), HasSubstr("unknown node type 'test/Nope'"));
  EXPECT_THAT(r.message(), HasSubstr("(list_node_types lists all " + std::to_string(testRegistry().ids().size()) + ")"));
}

TEST(Registry, GeneratesNamesAndRefusesBadOnes) {
  Graph g(testRegistry());
  EXPECT_EQ(g.addNode("test/OptionalSum").value(), "optional_sum_1");
  EXPECT_EQ(g.addNode("test/OptionalSum").value(), "optional_sum_2");
  EXPECT_THAT(g.addNode("test/Relay", "has space").message(), HasSubstr("node name 'has space'"));
  add(g, "test/Relay", "r");
  EXPECT_THAT(g.addNode("test/Relay", "r").message(), HasSubstr("a node named 'r' already exists"));
}

TEST(FunctionNode, DeducesPortsFromTheSignature) {
  NodeRegistry r = testRegistry();
  ASSERT_TRUE(registerFunction(r, "fn/Add", &plus, "adds", {"a", "b"}, {"sum"}));
  ASSERT_TRUE(
      registerFunction(r, "fn/DivMod", [](int a, int b) { return std::make_tuple(a / b, a % b); }, "divides", {}, {"q", "r"}));
  auto m = r.find("fn/DivMod")->manifest;
  ASSERT_EQ(m->inputs.size(), 2u);
  EXPECT_EQ(m->inputs[0].name, "in0");
  EXPECT_EQ(m->outputs[1].name, "r");
  EXPECT_EQ(m->outputs[1].type, typeOf<int>());
  auto wrong = registerFunction(r, "fn/Wrong", &plus, "adds", {"only_one"}, {});
  EXPECT_THAT(wrong.message(), HasSubstr("has 2 inputs and 1 outputs"));

  Graph g(std::move(r));
  ASSERT_TRUE(buildFromText(g, R"(
    nodes:
      - {name: fa, type: test/Feeder}
      - {name: fb, type: test/Feeder}
      - {name: sum, type: fn/Add}
      - {name: dm, type: fn/DivMod}
      - {name: q, type: test/Collector}
      - {name: rem, type: test/Collector}
    connections: [{from: fa/out, to: sum/a}, {from: fb/out, to: sum/b}, {from: sum/sum, to: dm/in0},
                  {from: fb/out, to: dm/in1}, {from: dm/q, to: q/in}, {from: dm/r, to: rem/in}])"));
  g.start();
  object<Feeder>(g, "fa")->feed(11);
  object<Feeder>(g, "fb")->feed(3);
  ASSERT_TRUE(object<Collector>(g, "rem")->waitFor(1));
  ASSERT_TRUE(object<Collector>(g, "q")->waitFor(1));
  EXPECT_EQ(object<Collector>(g, "q")->ints(), std::vector<int>{4});  // (11 + 3) / 3
  EXPECT_EQ(object<Collector>(g, "rem")->ints(), std::vector<int>{2});  // (11 + 3) % 3
}

TEST(Registry, AUserNamesATypeWithoutItsPackageAndAMisspeltOneGetsTheClosest) {
  NodeRegistry r = testRegistry();
  ASSERT_TRUE(r.add<Doubler>("other/Relay"));  // two packages with a Relay
  Graph g(r);
  auto added = g.addNode("Gain", "");  // unique without its package: test/Gain
  ASSERT_TRUE(added) << added.message();
  EXPECT_EQ(added.value(), "gain_1");
  EXPECT_EQ(findNode(g.describe(), "gain_1")->type, "test/Gain");  // saved under its whole id

  NodeDescription d;  // a description (add_node's way) too, its parameters applied
  d.name = "c", d.type = "Counter";
  ASSERT_TRUE(g.addNode(d));
  EXPECT_EQ(findNode(g.describe(), "c")->type, "test/Counter");

  EXPECT_EQ(g.addNode("Relay", "r").message(), "node type 'Relay' is ambiguous: other/Relay or test/Relay; give the whole id");
  EXPECT_TRUE(g.addNode("test/Relay", "r"));
  auto typo = g.addNode("Countr", "x");
  ASSERT_FALSE(typo);
  EXPECT_THAT(typo.message(), HasSubstr("unknown node type 'Countr': did you mean test/Counter?"));
  EXPECT_THAT(typo.message(), HasSubstr("list_node_types lists all"));
  EXPECT_THAT(g.addNode("test/collecter", "x").message(), HasSubstr("did you mean test/Collector?"));
  EXPECT_THAT(r.closest("Tick"), ::testing::ElementsAre("test/Ticker"));  // part of a name
  EXPECT_TRUE(r.closest("Zebra").empty());
  EXPECT_THAT(g.addNode("Zebra", "x").message(), ::testing::Not(HasSubstr("did you mean")));
}

TEST(NodeNames, ANewNodeIsNamedAfterItsTypeInSnakeCase) {
  EXPECT_EQ(apex::nodeBaseName("apex_nodes/GaussianBlur"), "gaussian_blur");
  EXPECT_EQ(apex::nodeBaseName("my_nodes/HSVFilter"), "hsv_filter");  // was "hsvfilter" here, "h_s_v_filter" in the panel
  EXPECT_EQ(apex::nodeBaseName("PointCloud2Publisher"), "point_cloud2_publisher");
  EXPECT_EQ(apex::nodeBaseName("a/SAC_Model"), "sac_model");
}
