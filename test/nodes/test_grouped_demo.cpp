// The demo graph grouped into subgraphs (graphs/demo.yaml, camera_detector.yaml,
// cloud_filter.yaml) against the paper's flat pipeline (graphs/paper_pipeline.yaml): on the
// synthetic demo bag both find every sign, so their outputs are the same, frame by frame
// (on photographs only the sign detector does: test/ros/photographs_check.sh). Node types
// through pluginlib.
#include <gmock/gmock.h>
#include <ros/package.h>

#include <map>
#include <mutex>

#include "apex/core/graph_file.hpp"
#include "apex_nodes/cloud.hpp"
#include "apex_nodes/types.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;

namespace {

/** What one graph made of the bag: the sign count and the filtered cloud's size, per frame. */
struct Outputs {
  std::mutex m;
  std::vector<int> counts;
  std::vector<std::size_t> points;
};

void play(const std::string& graph_file, const std::string& count_node, const std::string& cloud_node,
          const std::string& cloud_port, Outputs& out) {
  Graph g(pluginRegistry());
  auto loaded = loadGraphFile(g, ros::package::getPath("apex") + "/graphs/" + graph_file);
  ASSERT_TRUE(loaded) << loaded.message();
  for (const char* publisher : {"overlay_out", "cloud_out"}) ASSERT_TRUE(g.removeNode(publisher));  // no ROS here
  ASSERT_TRUE(g.setParameter("bag", "file", APEX_DEMO_BAG));
  ASSERT_TRUE(g.setParameter("bag", "rate", "0"));  // as fast as it goes
  ASSERT_TRUE(g.setTap(count_node, "count", [&](const Message& m) {
    if (auto c = m.as<int>()) {
      std::lock_guard<std::mutex> l(out.m);
      out.counts.push_back(*c);
    }
  }));
  ASSERT_TRUE(g.setTap(cloud_node, cloud_port, [&](const Message& m) {
    if (auto c = m.as<apex_nodes::Cloud>()) {
      std::lock_guard<std::mutex> l(out.m);
      out.points.push_back(apex_nodes::pointCount(*c));
    }
  }));
  g.start();
  EXPECT_TRUE(waitUntil(
      [&] {
        std::lock_guard<std::mutex> l(out.m);
        return out.counts.size() >= 40 && out.points.size() >= 40;
      },
      60));
  EXPECT_TRUE(g.waitIdle(kWait));
  g.stop();
}

TEST(GroupedDemo, SubgraphsGiveTheFlatGraphsOutputsFrameByFrame) {
  Outputs flat, grouped;
  play("paper_pipeline.yaml", "blobs", "voxels", "cloud", flat);
  play("demo.yaml", "camera_detector", "cloud_filter", "cloud", grouped);  // exported ports
  ASSERT_EQ(flat.counts.size(), 40u);
  EXPECT_EQ(grouped.counts, flat.counts);
  EXPECT_EQ(grouped.points, flat.points);
  int signs = 0;
  for (int c : flat.counts) signs += c;
  EXPECT_EQ(signs, 100);  // the demo bag's ground truth: the comparison is not of two empty runs
}

}  // namespace
