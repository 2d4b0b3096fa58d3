// The table demo's graph (graphs/table_objects.yaml) on its generated RGB-D frames: depth and
// colour → coloured cloud → table plane → its hull → the prism above it → clusters → features.
// Every frame must find the three boxes standing on the table, where the ground truth puts them.
// Node types through pluginlib; the graph's ROS publishers are taken out (no master here).
#include <gmock/gmock.h>
#include <ros/package.h>
#include <yaml-cpp/yaml.h>

#include <mutex>

#include "apex/core/graph_file.hpp"
#include "apex_nodes/cluster_features.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using apex_nodes::ClusterFeatures;

namespace {

TEST(TableDemo, EveryFrameFindsTheThreeBoxesWhereTheTruthPutsThem) {
  const YAML::Node truth = YAML::LoadFile(APEX_TABLE_TRUTH)["frames"];
  ASSERT_TRUE(truth && truth.size() > 0);
  Graph g(pluginRegistry());
  auto loaded = loadGraphFile(g, ros::package::getPath("apex") + "/graphs/table_objects.yaml");
  ASSERT_TRUE(loaded) << loaded.message();
  for (const char* ros_node : {"cloud_out", "boxes", "camera_pose"}) ASSERT_TRUE(g.removeNode(ros_node));
  ASSERT_TRUE(g.setParameter("bag", "file", APEX_TABLE_BAG));
  ASSERT_TRUE(g.setParameter("bag", "rate", "0"));  // as fast as it goes
  std::mutex m;
  std::vector<std::shared_ptr<const ClusterFeatures>> frames;
  ASSERT_TRUE(g.setTap("features", "features", [&](const Message& msg) {
    std::lock_guard<std::mutex> l(m);
    if (auto f = msg.as<ClusterFeatures>()) frames.push_back(f);
  }));
  g.start();
  EXPECT_TRUE(waitUntil(
      [&] {
        std::lock_guard<std::mutex> l(m);
        return frames.size() >= truth.size();
      },
      120))
      << "features of " << frames.size() << " frames";
  EXPECT_TRUE(g.waitIdle(kWait));
  g.stop();
  for (const auto& s : g.nodeStats(0)) EXPECT_EQ(s.error, "") << s.name;
  ASSERT_EQ(frames.size(), truth.size());
  for (std::size_t f = 0; f < frames.size(); ++f) {
    ASSERT_EQ(frames[f]->clusters.size(), 3u) << "frame " << f;
    // Each true box has a cluster near its centre: the camera sees only a box's top and front, so
    // the cluster's box is the visible part's, a few centimetres off the whole box's.
    for (const auto& box : truth[f]["boxes"]) {
      const Eigen::Vector3d centre(box["centre"][0].as<double>(), box["centre"][1].as<double>(), box["centre"][2].as<double>());
      double nearest = 1e9;
      for (const auto& c : frames[f]->clusters) nearest = std::min(nearest, (c.centre() - centre).norm());
      EXPECT_LT(nearest, 0.08) << "frame " << f << ": no cluster near the box at " << centre.transpose();
    }
  }
}

}  // namespace
