// Point-cloud nodes against the same PCL call made directly (point-exact).
#include <gmock/gmock.h>
#include <pcl/filters/extract_indices.h>
#include <pcl/filters/passthrough.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/segmentation/sac_segmentation.h>
#include <sensor_msgs/LaserScan.h>

#include <pcl/common/transforms.h>

#include "apex_nodes/stamp.hpp"
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

TEST(CloudNodes, StatisticalOutlierRemovalMatchesPcl) {
  NodeHarness h("apex_nodes/StatisticalOutlierRemoval", {"cloud"}, "cloud");
  pcl::StatisticalOutlierRemoval<apex_nodes::PointT> f;
  f.setInputCloud(cloud()->points);
  f.setMeanK(20);
  f.setStddevMulThresh(1.0);
  PclCloud want;
  f.filter(want);
  expectSame(*out(h.run(cloud())).points, want);
}

/** A floor (y = 0.5) with scattered points above it: a plane and two blobs. */
std::shared_ptr<const Cloud> scene() {
  auto points = std::make_shared<PclCloud>();
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) points->push_back(apex_nodes::PointT(0.05f * i, 0.5f, 0.05f * j));
  for (int i = 0; i < 100; ++i) {
    points->push_back(apex_nodes::PointT(0.2f + 0.001f * (i % 10), 0.1f + 0.001f * (i / 10), 0.2f));
    points->push_back(apex_nodes::PointT(1.5f + 0.001f * (i % 10), 0.1f + 0.001f * (i / 10), 1.5f));
  }
  auto c = std::make_shared<Cloud>();
  c->header.frame_id = "lidar";
  c->points = points;
  return c;
}

TEST(CloudNodes, PlaneSegmentationSplitsThePlane) {
  NodeHarness h("apex_nodes/PlaneSegmentation", {"cloud"}, "inliers");
  EXPECT_EQ(out(h.run(scene())).points->size(), 1600u);  // the whole floor
  NodeHarness c("apex_nodes/PlaneSegmentation", {"cloud"}, "coefficients");
  auto coefficients = c.run(scene()).as<std::vector<double>>();
  ASSERT_TRUE(coefficients);
  ASSERT_EQ(coefficients->size(), 4u);
  EXPECT_NEAR(std::abs((*coefficients)[1]), 1.0, 1e-3);  // normal along y
  EXPECT_NEAR((*coefficients)[3] / (*coefficients)[1], -0.5, 1e-3);
}

TEST(CloudNodes, EuclideanClusteringMatchesPcl) {
  NodeHarness h("apex_nodes/EuclideanClustering", {"cloud"}, "clusters");
  h.set("tolerance", "0.02");
  auto clusters = h.run(scene()).as<apex_nodes::Clusters>();
  ASSERT_TRUE(clusters);
  auto tree = std::make_shared<pcl::search::KdTree<apex_nodes::PointT>>();
  tree->setInputCloud(scene()->points);
  std::vector<pcl::PointIndices> want;
  pcl::EuclideanClusterExtraction<apex_nodes::PointT> ec;
  ec.setClusterTolerance(0.02);
  ec.setMinClusterSize(50);
  ec.setMaxClusterSize(1000000);
  ec.setSearchMethod(tree);
  ec.setInputCloud(scene()->points);
  ec.extract(want);
  ASSERT_EQ(clusters->clusters.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_EQ(clusters->clusters[i]->size(), want[i].indices.size());
}

TEST(CloudNodes, LaserScanToCloudKeepsValidRanges) {
  NodeHarness h("apex_nodes/LaserScanToCloud", {"scan"}, "cloud");
  auto scan = std::make_shared<sensor_msgs::LaserScan>();
  scan->header.frame_id = "lidar";
  scan->angle_min = 0;
  scan->angle_increment = M_PI / 2;
  scan->range_min = 0.1f, scan->range_max = 10.f;
  scan->ranges = {1.f, std::nanf(""), 2.f, 50.f};
  const auto& c = out(h.run(std::shared_ptr<const sensor_msgs::LaserScan>(scan)));
  ASSERT_EQ(c.points->size(), 2u);
  EXPECT_NEAR((*c.points)[0].x, 1.0, 1e-6);
  EXPECT_NEAR((*c.points)[1].x, -2.0, 1e-6);  // 180 degrees
  scan->ranges = {std::nanf(""), std::nanf("")};
  EXPECT_TRUE(h.run(std::shared_ptr<const sensor_msgs::LaserScan>(scan)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("has none within"));
}

TEST(CloudNodes, ANanOnlyCloudIsAnError) {
  NodeHarness h("apex_nodes/PassThrough", {"cloud"}, "cloud");
  auto nan = std::make_shared<Cloud>();
  auto points = std::make_shared<PclCloud>();
  points->push_back(apex_nodes::PointT(std::nanf(""), 0, 0));
  nan->points = points;
  EXPECT_TRUE(h.run(std::shared_ptr<const Cloud>(nan)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("none of them finite"));
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

namespace {

TEST(CloudNodes, TransformCloudMatchesPclAndChecksFrames) {
  NodeHarness h("apex_nodes/TransformCloud", {"cloud", "transform"}, "cloud");
  auto t = std::make_shared<geometry_msgs::TransformStamped>();
  t->header.frame_id = "base_link";
  t->child_frame_id = "lidar";
  t->transform.translation.x = 1.0;
  t->transform.rotation.z = std::sin(M_PI / 4), t->transform.rotation.w = std::cos(M_PI / 4);  // 90 deg about z
  const Message m_out = h.run({Message::share<Cloud>(cloud()), Message::share<geometry_msgs::TransformStamped>(t)});
  ASSERT_TRUE(m_out.as<Cloud>());
  const Cloud& got = *m_out.as<Cloud>();
  EXPECT_EQ(got.header.frame_id, "base_link");
  Eigen::Affine3f m = Eigen::Affine3f::Identity();
  m.translate(Eigen::Vector3f(1, 0, 0));
  m.rotate(Eigen::AngleAxisf(static_cast<float>(M_PI / 2), Eigen::Vector3f::UnitZ()));
  PclCloud want;
  pcl::transformPointCloud(*cloud()->points, want, m);
  ASSERT_EQ(got.points->size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) ASSERT_NEAR((*got.points)[i].x, want[i].x, 1e-5);
  t->child_frame_id = "camera";
  EXPECT_TRUE(h.run({Message::share<Cloud>(cloud()), Message::share<geometry_msgs::TransformStamped>(t)}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("the transform maps frame 'camera', the cloud is in 'lidar'"));
}

}  // namespace
