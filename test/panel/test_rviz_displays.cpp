// "Show in rviz" without rviz: which display a port's message type gets, and what happens to the
// displays the panel made as the graph changes (rviz_displays.hpp). The graph is the model tests'
// clock -> relay -> count (graph_model_fixture.hpp).
#include <gtest/gtest.h>

#include "apex_rviz_plugin/rviz_displays.hpp"
#include "graph_model_fixture.hpp"

namespace {

using apex_rviz_plugin::DisplayChange;
using apex_rviz_plugin::FollowedDisplays;
using apex_rviz_plugin::noRvizDisplayReason;
using apex_rviz_plugin::rvizDisplayFor;
using Kind = DisplayChange::Kind;
using graph_model_fixture::graph;

/** "kind id node/port [name]" for each change: failures say what happened. */
std::vector<std::string> text(const std::vector<DisplayChange>& changes) {
  static const char* kKinds[] = {"rename", "remove", "enable", "disable"};
  std::vector<std::string> out;
  for (const auto& c : changes)
    out.push_back(std::string(kKinds[static_cast<int>(c.kind)]) + " " + std::to_string(c.id) + " " + c.node + "/" + c.port +
                  (c.name.empty() ? "" : " " + c.name));
  return out;
}

apex::GraphState renamed(apex::GraphState g, const std::string& from, const std::string& to) {
  for (auto& n : g.nodes)
    if (n.name == from) n.name = to;
  for (auto& c : g.connections) {
    if (c.from_node == from) c.from_node = to;
    if (c.to_node == from) c.to_node = to;
  }
  return g;
}

TEST(RvizDisplays, EachResultTypeHasItsDisplayAndTopicProperty) {
  const std::pair<const char*, std::pair<const char*, const char*>> table[] = {
      {"sensor_msgs/Image", {"rviz/Image", "Image Topic"}},
      {"sensor_msgs/PointCloud2", {"rviz/PointCloud2", "Topic"}},
      {"visualization_msgs/MarkerArray", {"rviz/MarkerArray", "Marker Topic"}},
      {"visualization_msgs/Marker", {"rviz/Marker", "Marker Topic"}},
      {"geometry_msgs/PoseStamped", {"rviz/Pose", "Topic"}},
      {"geometry_msgs/PoseArray", {"rviz/PoseArray", "Topic"}},
      {"sensor_msgs/LaserScan", {"rviz/LaserScan", "Topic"}},
      {"tf2_msgs/TFMessage", {"rviz/TF", ""}},
  };
  for (const auto& [type, display] : table) {
    const auto d = rvizDisplayFor(type);
    ASSERT_TRUE(d) << type;
    EXPECT_EQ(d->rviz_class, display.first) << type;
    EXPECT_EQ(d->topic_property, display.second) << type;
    EXPECT_EQ(noRvizDisplayReason(type), "") << type;
  }
}

TEST(RvizDisplays, TypesWithoutADisplaySayWhy) {
  EXPECT_FALSE(rvizDisplayFor("std_msgs/Int32"));
  EXPECT_EQ(noRvizDisplayReason("std_msgs/Int32"), "rviz has no display for std_msgs/Int32");
  EXPECT_EQ(noRvizDisplayReason("apex/Regions"), "rviz has no display for apex/Regions");
  EXPECT_EQ(noRvizDisplayReason("geometry_msgs/TransformStamped"),
            "rviz shows transforms from /tf only (its TF display), not from a topic");
  EXPECT_EQ(noRvizDisplayReason(""), "its ROS message type is known from its first message only");
}

TEST(FollowedDisplays, OneDisplayPerPortNamedAfterIt) {
  FollowedDisplays f;
  const int a = f.follow("clock", "count");
  EXPECT_EQ(f.follow("clock", "count"), a);  // shown again: the same display
  EXPECT_NE(f.follow("count", "count"), a);
  EXPECT_EQ(f.find("clock", "count"), a);
  EXPECT_EQ(f.find("clock", "time"), -1);
  EXPECT_EQ(FollowedDisplays::displayName("camera_detector", "overlay"), "apex: camera_detector/overlay");
  EXPECT_TRUE(f.enabled(a));
}

TEST(FollowedDisplays, UnchangedGraphChangesNothing) {
  FollowedDisplays f;
  f.follow("clock", "count"), f.follow("count", "count");
  EXPECT_TRUE(f.update(graph(1)).empty());
  EXPECT_TRUE(f.update(graph(2)).empty());
}

TEST(FollowedDisplays, RemovedNodeRemovesItsDisplaysOnly) {
  FollowedDisplays f;
  const int relay = f.follow("relay", "out"), clock = f.follow("clock", "count");
  auto g = graph(2);
  g.nodes.erase(g.nodes.begin() + 1);  // the relay
  g.connections = {g.connections[2]};
  EXPECT_EQ(text(f.update(g)), (std::vector<std::string>{"remove " + std::to_string(relay) + " relay/out"}));
  EXPECT_EQ(f.find("relay", "out"), -1);
  EXPECT_TRUE(f.enabled(clock));
  EXPECT_TRUE(f.update(g).empty());  // reported once
}

TEST(FollowedDisplays, PortGoneRemovesTheDisplay) {
  FollowedDisplays f;
  const int id = f.follow("clock", "time");
  auto g = graph(2);
  g.nodes[0].ports.erase(g.nodes[0].ports.begin() + 1);
  EXPECT_EQ(text(f.update(g)), (std::vector<std::string>{"remove " + std::to_string(id) + " clock/time"}));
}

TEST(FollowedDisplays, RenameFollowsTheNodeAndWaitsForItsNewTopic) {
  FollowedDisplays f;
  const int id = f.follow("relay", "out");
  f.expectRename("relay", "pass");
  EXPECT_TRUE(f.update(graph(1)).empty());  // the graph from before the rename
  const auto g = renamed(graph(2), "relay", "pass");
  EXPECT_EQ(text(f.update(g)), (std::vector<std::string>{"rename " + std::to_string(id) + " pass/out apex: pass/out"}));
  EXPECT_FALSE(f.enabled(id));  // its topic moved: the runtime forgot the old inspection
  EXPECT_EQ(f.find("pass", "out"), id);
  EXPECT_EQ(f.follow("pass", "out"), id);  // inspected under the new name
  EXPECT_TRUE(f.enabled(id));
  EXPECT_TRUE(f.update(g).empty());
}

TEST(FollowedDisplays, RenamedSubgraphTakesItsInnerNodesDisplays) {
  FollowedDisplays f;
  auto g = graph(1);
  g.nodes[1].name = "detector";
  g.nodes[1].subgraph = "inline";
  apex::NodeInfo inner = g.nodes[2];
  inner.name = "detector/blobs";
  g.nodes.push_back(inner);
  const int id = f.follow("detector/blobs", "count");
  f.expectRename("detector", "finder");
  auto after = g;
  after.nodes[1].name = "finder", after.nodes[3].name = "finder/blobs";
  EXPECT_EQ(text(f.update(after)),
            (std::vector<std::string>{"rename " + std::to_string(id) + " finder/blobs/count apex: finder/blobs/count"}));
}

TEST(FollowedDisplays, RemovalWithoutARenameExpectedIsNotTakenForOne) {
  FollowedDisplays f;
  const int id = f.follow("relay", "out");
  auto g = renamed(graph(2), "relay", "pass");  // as a rename looks, but none was sent
  EXPECT_EQ(text(f.update(g)), (std::vector<std::string>{"remove " + std::to_string(id) + " relay/out"}));
}

TEST(FollowedDisplays, RefusedRenameIsForgotten) {
  FollowedDisplays f;
  const int id = f.follow("relay", "out");
  auto g = graph(1);
  apex::NodeInfo pass = g.nodes[1];
  pass.name = "pass";
  g.nodes.push_back(pass);
  f.expectRename("relay", "pass");  // refused: the name is taken
  EXPECT_TRUE(f.update(g).empty());
  g.nodes.erase(g.nodes.begin() + 1);  // then the relay is removed
  EXPECT_EQ(text(f.update(g)), (std::vector<std::string>{"remove " + std::to_string(id) + " relay/out"}));
}

TEST(FollowedDisplays, UnlinkedInputDisablesAndRelinkingEnables) {
  FollowedDisplays f;
  const int id = f.follow("count", "count");
  auto g = graph(2);
  g.connections.erase(g.connections.begin() + 1);  // relay/out -> count/in
  EXPECT_EQ(text(f.update(g)), (std::vector<std::string>{"disable " + std::to_string(id) + " count/count"}));
  EXPECT_FALSE(f.enabled(id));
  EXPECT_EQ(text(f.update(graph(3))), (std::vector<std::string>{"enable " + std::to_string(id) + " count/count"}));
  EXPECT_TRUE(f.enabled(id));
}

TEST(FollowedDisplays, OptionalInputsNeedNoLink) {
  FollowedDisplays f;
  const int id = f.follow("count", "count");
  auto g = graph(2);
  g.nodes[2].ports[0].optional = true;
  g.connections.erase(g.connections.begin() + 1);
  EXPECT_TRUE(f.update(g).empty());
  EXPECT_TRUE(f.enabled(id));
}

TEST(FollowedDisplays, ForgottenDisplayIsNoLongerFollowed) {
  FollowedDisplays f;
  const int id = f.follow("relay", "out");
  f.forget(id);  // deleted by hand in rviz
  auto g = graph(2);
  g.nodes.erase(g.nodes.begin() + 1);
  EXPECT_TRUE(f.update(g).empty());
  EXPECT_FALSE(f.enabled(id));
}

}  // namespace
