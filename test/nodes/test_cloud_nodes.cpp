// Point-cloud nodes against the same PCL call made directly (point-exact).
#include <gmock/gmock.h>
#include <pcl/filters/passthrough.h>
#include <pcl/filters/voxel_grid.h>

#include "apex_nodes/types.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using apex_nodes::Cloud;
using apex_nodes::PclCloud;
using ::testing::HasSubstr;

namespace {

std::shared_ptr<const Cloud> cloud() {
  auto points = std::make_shared<PclCloud>();
  for (int i = 0; i < 2000; ++i) points->push_back(apex_nodes::PointT(0.01f * (i % 50), 0.02f * (i % 37), 0.003f * i));
  auto c = std::make_shared<Cloud>();
  c->header.frame_id = "lidar";
  c->header.stamp = ros::Time(5, 0);
  c->points = points;
  return c;
}

void expectSame(const PclCloud& a, const PclCloud& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].x, b[i].x) << i;
    ASSERT_EQ(a[i].y, b[i].y) << i;
    ASSERT_EQ(a[i].z, b[i].z) << i;
  }
}

const Cloud& out(const Message& m) {
  auto c = m.as<Cloud>();
  if (!c) throw std::runtime_error("expected a cloud, got " + m.typeName());
  EXPECT_EQ(c->header.frame_id, "lidar");
  return *c;
}

TEST(CloudNodes, PassThroughMatchesPcl) {
  NodeHarness h("apex_nodes/PassThrough", {"cloud"}, "cloud");
  h.set("limits", "[1.0, 4.0]");
  pcl::PassThrough<apex_nodes::PointT> f;
  f.setInputCloud(cloud()->points);
  f.setFilterFieldName("z");
  f.setFilterLimits(1.0f, 4.0f);
  PclCloud want;
  f.filter(want);
  expectSame(*out(h.run(cloud())).points, want);
  EXPECT_THAT(h.graph().setParameter("node", "limits", "[4, 1]").message(), HasSubstr("low 4 is above high 1"));
}

TEST(CloudNodes, VoxelGridMatchesPcl) {
  NodeHarness h("apex_nodes/VoxelGrid", {"cloud"}, "cloud");
  h.set("leaf_size", "0.1");
  pcl::VoxelGrid<apex_nodes::PointT> f;
  f.setInputCloud(cloud()->points);
  f.setLeafSize(0.1f, 0.1f, 0.1f);
  PclCloud want;
  f.filter(want);
  expectSame(*out(h.run(cloud())).points, want);
}

TEST(CloudNodes, AnEmptyCloudIsAnError) {
  NodeHarness h("apex_nodes/VoxelGrid", {"cloud"}, "cloud");
  auto empty = std::make_shared<Cloud>();
  empty->points = std::make_shared<PclCloud>();
  EXPECT_TRUE(h.run(std::shared_ptr<const Cloud>(empty)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("received an empty point cloud"));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
