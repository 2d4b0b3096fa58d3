// The critical path the panel colours: through the slowest sender at each node, by live latency
// where every sender has one, else by firing times summed along the way.
#include <gmock/gmock.h>

#include "apex_rviz_plugin/critical_path.hpp"

using namespace apex_rviz_plugin;

namespace {

apex::Connection link(const std::string& from, const std::string& to, const std::string& kind = "data") {
  apex::Connection c;
  c.from_node = from, c.from_port = "out", c.to_node = to, c.to_port = from == "blur" ? "a" : "b", c.kind = kind;
  return c;
}

/** cam -> blur -> join.a, cam -> edges -> join.b, join -> sink; a clock's event into join. */
apex::GraphState twoBranches() {
  apex::GraphState g;
  g.connections = {link("cam", "blur"),   link("cam", "edges"), link("blur", "join"),
                   link("edges", "join"), link("join", "sink"), link("clock", "join", "event")};
  return g;
}

std::map<std::string, apex::NodeStatus> times(std::map<std::string, std::pair<double, double>> mean_and_latency) {
  std::map<std::string, apex::NodeStatus> out;
  for (const auto& [name, ml] : mean_and_latency) {
    out[name].name = name;
    out[name].mean_ms = ml.first;
    out[name].latency_p50_ms = ml.second;
  }
  return out;
}

std::vector<std::string> nodes(const std::vector<apex::Connection>& path) {
  std::vector<std::string> out;
  if (!path.empty()) out.push_back(path.front().from_node);
  for (const auto& c : path) out.push_back(c.to_node);
  return out;
}

TEST(CriticalPath, GoesThroughTheSlowerBranchByFiringTimesWithoutLiveStamps) {
  const auto status =
      times({{"cam", {0.1, -1}}, {"blur", {5, -1}}, {"edges", {1, -1}}, {"join", {0.5, -1}}, {"sink", {0.1, -1}}});
  const auto path = criticalPath(twoBranches(), status, "sink");
  EXPECT_THAT(nodes(path), ::testing::ElementsAre("cam", "blur", "join", "sink"));
  EXPECT_EQ(describeCriticalPath(path, status, "sink"), "cam → blur → join → sink: 5.70 ms of firing time");
}

TEST(CriticalPath, FollowsTheLatestFramesWhereEverySenderHasALiveLatency) {
  // edges is faster to fire but its frames come later (say it waits on a slow group)
  const auto status =
      times({{"cam", {0.1, 1}}, {"blur", {5, 7}}, {"edges", {1, 20}}, {"join", {0.5, 21}}, {"sink", {0.1, 21.5}}});
  const auto path = criticalPath(twoBranches(), status, "sink");
  EXPECT_THAT(nodes(path), ::testing::ElementsAre("cam", "edges", "join", "sink"));
  EXPECT_EQ(describeCriticalPath(path, status, "sink"),
            "cam → edges → join → sink: 1.70 ms of firing time (latency p50 21.5 ms)");
}

TEST(CriticalPath, ASourceOrAnUnknownNodeHasNone) {
  EXPECT_TRUE(criticalPath(twoBranches(), {}, "cam").empty());
  EXPECT_TRUE(criticalPath(twoBranches(), {}, "ghost").empty());
  EXPECT_EQ(describeCriticalPath({}, {}, "cam"), "cam has no data inputs: no critical path");
}

TEST(CriticalPath, ACycleShownForAMomentEndsThePath) {
  apex::GraphState g;
  g.connections = {link("a", "b"), link("b", "a"), link("b", "sink")};
  EXPECT_THAT(nodes(criticalPath(g, {}, "sink")), ::testing::ElementsAre("a", "b", "sink"));
}

}  // namespace
