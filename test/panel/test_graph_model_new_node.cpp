// The panel's model: a link dragged to empty canvas, or a link a new node goes into, without a
// display. Which types may take it (the runtime's rules over the graph with the new node in it),
// and the node added with its links as one edit.
#include <gmock/gmock.h>

#include "apex_rviz_plugin/graph_model.hpp"
#include "graph_model_fixture.hpp"

using namespace apex_rviz_plugin;
using namespace graph_model_fixture;
using ::testing::ElementsAre;

namespace {

apex::NodeTypeInfo type(const std::string& id, std::vector<apex::PortInfo> own) {
  apex::NodeTypeInfo t;
  t.id = id;
  t.ports = std::move(own);
  for (auto builtin : {port("enable", "slot", ""), port("disable", "slot", ""), port("processed", "trigger", "")})
    t.ports.push_back(builtin);
  return t;
}

/** A number filter, an image filter, a type with an int parameter that has ports, one with a slot, one with nothing of its own.
 */
std::vector<apex::NodeTypeInfo> types() {
  auto tuned = type("t/Tuned", {});
  tuned.parameters = {param("threshold", "3", true), param("label", "'x'")};
  tuned.parameters[0].type = "int", tuned.parameters[1].type = "string";
  tuned.parameters[0].default_value = "3", tuned.parameters[1].default_value = "'x'";
  return {type("t/Scale", {port("in", "input", "double"), port("out", "output", "double")}),
          type("t/Blur", {port("image", "input", "apex_nodes/Image"), port("image", "output", "apex_nodes/Image")}),
          tuned,
          type("t/Relay", {port("in", "input", "any"), port("out", "output", "any")}),
          type("t/Pulse", {}),
          type("t/Resettable", {port("reset", "slot", "")})};
}

std::vector<std::string> offered(const std::vector<NewLink>& links) {
  std::vector<std::string> out;
  for (const auto& l : links) out.push_back(l.type + " " + l.port);
  return out;
}

TEST(GraphModelNewNode, IsAsAddNodeMakesIt) {
  const auto n = GraphModel::newNode(types()[2], "tuned_1");
  EXPECT_EQ(n.name, "tuned_1");
  ASSERT_EQ(n.parameters.size(), 2u);
  EXPECT_EQ(n.parameters[0].value, "3");  // at its default
  std::vector<std::string> ports;
  for (const auto& p : n.ports) ports.push_back(p.kind + " " + p.name + " " + p.type);
  EXPECT_THAT(ports, ElementsAre("slot enable ", "slot disable ", "trigger processed ", "param_in threshold int",
                                 "param_out threshold int"));
}

TEST(GraphModelNewNode, AnOutputIsOfferedTheTypesThatTakeIt) {
  GraphModel m;
  m.update(graph(1));
  // clock/count is an int: an any input or an int parameter with ports takes it, a double or image input does not
  EXPECT_THAT(offered(m.linkable(types(), "clock", "count", true)), ElementsAre("t/Tuned threshold", "t/Relay in"));
  // a trigger: the types with a slot of their own first, then those with only the slots every node has
  EXPECT_THAT(
      offered(m.linkable(types(), "clock", "processed", true)),
      ElementsAre("t/Resettable reset", "t/Scale enable", "t/Blur enable", "t/Tuned enable", "t/Relay enable", "t/Pulse enable"));
}

TEST(GraphModelNewNode, AnInputInUseIsOfferedTheTypesThatFeedIt) {
  GraphModel m;
  m.update(graph(1));
  // count/in takes anything and is fed by the relay: a new node's output replaces that link
  EXPECT_THAT(offered(m.linkable(types(), "count", "in", false)),
              ElementsAre("t/Scale out", "t/Blur image", "t/Tuned threshold", "t/Relay out"));
  EXPECT_THAT(offered(m.linkable(types(), "count", "reset", false)),
              ElementsAre("t/Scale processed", "t/Blur processed", "t/Tuned processed", "t/Relay processed", "t/Pulse processed",
                          "t/Resettable processed"));
}

TEST(GraphModelNewNode, AddedWithItsLinkInOneEdit) {
  GraphModel m;
  m.update(graph(1));
  apex::Connection fed;  // clock/count -> a new relay
  fed.from_node = "clock", fed.from_port = "count", fed.to_node = "relay_2", fed.to_port = "in";
  Edit e = m.addLinked("t/Relay", "relay_2", 10, 20, fed);
  EXPECT_EQ(e.label, "Add relay_2 fed by clock/count");
  EXPECT_THAT(services(e.apply), ElementsAre("add_node", "set_ui", "connect"));
  EXPECT_THAT(services(e.revert), ElementsAre("disconnect", "remove_node"));

  apex::Connection feeds;  // a new scale -> count/in, which the relay feeds now: that link goes, and comes back on undo
  feeds.from_node = "scale_1", feeds.from_port = "out", feeds.to_node = "count", feeds.to_port = "in";
  e = m.addLinked("t/Scale", "scale_1", 10, 20, feeds);
  EXPECT_EQ(e.label, "Add scale_1 feeding count/in");
  EXPECT_THAT(services(e.apply), ElementsAre("add_node", "set_ui", "disconnect", "connect"));
  EXPECT_THAT(services(e.revert), ElementsAre("disconnect", "connect", "remove_node"));
  EXPECT_EQ(std::get<apex::Connect::Request>(e.revert[1].request).from_node, "relay");
}

std::vector<std::string> offered(const std::vector<NewInsert>& inserts) {
  std::vector<std::string> out;
  for (const auto& i : inserts) out.push_back(i.type + " " + i.in + " " + i.out);
  return out;
}

apex::Connection connection(const std::string& from, const std::string& from_port, const std::string& to,
                            const std::string& to_port) {
  apex::Connection c;
  c.from_node = from, c.from_port = from_port, c.to_node = to, c.to_port = to_port;
  return c;
}

TEST(GraphModelNewNode, ALinkIsOfferedTheTypesThatTakeItsSourceAndFeedItsTarget) {
  GraphModel m;
  m.update(graph(1));
  // relay/out (any) -> count/in (any): every type with an input and an output of its own
  EXPECT_THAT(offered(m.insertable(types(), connection("relay", "out", "count", "in"))),
              ElementsAre("t/Scale in out", "t/Blur image image", "t/Tuned threshold threshold", "t/Relay in out"));
  // clock/count (an int) -> relay/in: a double or image input does not take it
  EXPECT_THAT(offered(m.insertable(types(), connection("clock", "count", "relay", "in"))),
              ElementsAre("t/Tuned threshold threshold", "t/Relay in out"));
  // a trigger into a slot: a slot of its own first, the events every node has otherwise
  EXPECT_THAT(offered(m.insertable(types(), connection("clock", "processed", "count", "reset"))),
              ElementsAre("t/Resettable reset processed", "t/Scale enable processed", "t/Blur enable processed",
                          "t/Tuned enable processed", "t/Relay enable processed", "t/Pulse enable processed"));
}

TEST(GraphModelNewNode, InsertedIntoALinkInOneEditThatGivesTheLinkBack) {
  GraphModel m;
  m.update(graph(1));
  const apex::Connection link = connection("relay", "out", "count", "in");
  Edit e = m.addInserted("t/Relay", "relay_2", 10, 20, link, "in", "out");
  EXPECT_EQ(e.label, "Insert relay_2 into relay/out -> count/in");
  EXPECT_THAT(services(e.apply), ElementsAre("add_node", "set_ui", "connect", "disconnect", "connect"));
  auto ends = [](const Call& c) {
    const auto& r = std::get<apex::Connect::Request>(c.request);
    return r.from_node + "/" + r.from_port + " -> " + r.to_node + "/" + r.to_port;
  };
  EXPECT_EQ(ends(e.apply[2]), "relay/out -> relay_2/in");
  EXPECT_EQ(ends(e.apply[3]), "relay/out -> count/in");
  EXPECT_EQ(ends(e.apply[4]), "relay_2/out -> count/in");
  EXPECT_THAT(services(e.revert), ElementsAre("disconnect", "connect", "disconnect", "remove_node"));
  EXPECT_EQ(ends(e.revert[1]), "relay/out -> count/in");

  // a slot takes many links: the old one is dropped as well, and comes back first on undo
  e = m.addInserted("t/Resettable", "resettable_1", 10, 20, connection("clock", "processed", "count", "reset"), "reset",
                    "processed");
  EXPECT_THAT(services(e.apply), ElementsAre("add_node", "set_ui", "connect", "connect", "disconnect"));
  EXPECT_EQ(ends(e.apply[4]), "clock/processed -> count/reset");
  EXPECT_THAT(services(e.revert), ElementsAre("connect", "disconnect", "disconnect", "remove_node"));
  EXPECT_EQ(ends(e.revert[0]), "clock/processed -> count/reset");
}

}  // namespace
