// Point-cloud nodes against the same PCL call made directly (point-exact), on clouds with colour
// (x, y, z, rgb), intensity or fields PCL has no type for (a lidar's ring): every field the input
// has comes out, with the values PCL's typed call gives.
#include <gmock/gmock.h>
#include <pcl/common/transforms.h>
#include <pcl/filters/crop_box.h>
#include <pcl/filters/passthrough.h>
#include <pcl/filters/radius_outlier_removal.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/segmentation/sac_segmentation.h>
#include <sensor_msgs/LaserScan.h>

#include "apex_nodes/cloud.hpp"
#include "apex_nodes/stamp.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using apex_nodes::Cloud;
using ::testing::HasSubstr;
using Rgb = pcl::PointCloud<pcl::PointXYZRGB>;
using Xyz = pcl::PointCloud<pcl::PointXYZ>;

namespace {

std_msgs::Header lidarHeader() {
  std_msgs::Header h;
  h.frame_id = "lidar";
  h.stamp = ros::Time(5, 123456789);  // nanoseconds: PCL's own header would keep microseconds
  return h;
}

/** 2000 coloured points on a slanted sheet. */
Rgb colouredPoints() {
  Rgb points;
  for (int i = 0; i < 2000; ++i) {
    pcl::PointXYZRGB p(std::uint8_t(i % 256), std::uint8_t((7 * i) % 256), std::uint8_t((13 * i) % 256));
    p.x = 0.01f * (i % 50), p.y = 0.02f * (i % 37), p.z = 0.003f * i;
    points.push_back(p);
  }
  return points;
}

std::shared_ptr<const Cloud> cloud() { return apex_nodes::makeCloud(lidarHeader(), colouredPoints()); }

/** x, y, z and colour, point by point. */
void expectSame(const Rgb& got, const Rgb& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(got[i].x, want[i].x) << i;
    ASSERT_EQ(got[i].y, want[i].y) << i;
    ASSERT_EQ(got[i].z, want[i].z) << i;
    ASSERT_EQ(got[i].rgba, want[i].rgba) << i;
  }
}

const Cloud& out(const Message& m) {
  auto c = m.as<Cloud>();
  if (!c) throw std::runtime_error("expected a cloud, got " + m.typeName());
  EXPECT_EQ(c->header, lidarHeader());
  return *c;
}

/** What a node sent, as coloured points, after checking it kept the input's fields. */
Rgb colours(const Message& m) {
  const Cloud& c = out(m);
  EXPECT_EQ(apex_nodes::fieldNames(*c.points), "x, y, z, rgb");
  return apex_nodes::typedPoints<pcl::PointXYZRGB>(c);
}

/** PCL's filter `F` on the coloured points, configured by `configure`. */
template <template <class> class F, class Configure>
Rgb pclResult(Configure configure) {
  F<pcl::PointXYZRGB> f;
  f.setInputCloud(std::make_shared<Rgb>(colouredPoints()));
  configure(f);
  Rgb want;
  f.filter(want);
  return want;
}

TEST(CloudNodes, PassThroughMatchesPclColoursIncluded) {
  NodeHarness h("apex_nodes/PassThrough", {"cloud"}, "cloud");
  h.set("limits", "[1.0, 4.0]");
  const Rgb want = pclResult<pcl::PassThrough>([](auto& f) {
    f.setFilterFieldName("z");
    f.setFilterLimits(1.0f, 4.0f);
  });
  ASSERT_GT(want.size(), 100u);
  expectSame(colours(h.run(cloud())), want);
  EXPECT_THAT(h.graph().setParameter("node", "limits", "[4, 1]").message(), HasSubstr("low 4 is above high 1"));
}

TEST(CloudNodes, CropBoxMatchesPclColoursIncluded) {
  NodeHarness h("apex_nodes/CropBox", {"cloud"}, "cloud");
  h.set("x", "[0.1, 0.3]"), h.set("y", "[0.0, 0.5]"), h.set("z", "[0.5, 5.0]");
  auto box = [](auto& f) {
    f.setMin(Eigen::Vector4f(0.1f, 0.0f, 0.5f, 1.f));
    f.setMax(Eigen::Vector4f(0.3f, 0.5f, 5.0f, 1.f));
  };
  const Rgb want = pclResult<pcl::CropBox>(box);
  ASSERT_GT(want.size(), 50u);
  expectSame(colours(h.run(cloud())), want);
  h.set("negative", "true");
  expectSame(colours(h.run(cloud())), pclResult<pcl::CropBox>([&](auto& f) { box(f), f.setNegative(true); }));
}

TEST(CloudNodes, VoxelGridMatchesPclColoursIncluded) {
  NodeHarness h("apex_nodes/VoxelGrid", {"cloud"}, "cloud");
  h.set("leaf_size", "0.1");
  const Rgb want = pclResult<pcl::VoxelGrid>([](auto& f) { f.setLeafSize(0.1f, 0.1f, 0.1f); });
  ASSERT_LT(want.size(), 1000u);
  expectSame(colours(h.run(cloud())), want);
}

TEST(CloudNodes, StatisticalOutlierRemovalMatchesPcl) {
  NodeHarness h("apex_nodes/StatisticalOutlierRemoval", {"cloud"}, "cloud");
  expectSame(colours(h.run(cloud())), pclResult<pcl::StatisticalOutlierRemoval>([](auto& f) {
               f.setMeanK(20);
               f.setStddevMulThresh(1.0);
             }));
}

TEST(CloudNodes, RadiusOutlierRemovalMatchesPcl) {
  NodeHarness h("apex_nodes/RadiusOutlierRemoval", {"cloud"}, "cloud");
  h.set("radius", "0.03"), h.set("min_neighbours", "2");
  const Rgb want = pclResult<pcl::RadiusOutlierRemoval>([](auto& f) {
    f.setRadiusSearch(0.03);
    f.setMinNeighborsInRadius(2);
  });
  ASSERT_LT(want.size(), 2000u);
  expectSame(colours(h.run(cloud())), want);
}

/** x, y, z, intensity and a field no PCL point type has (a lidar's ring, uint16). */
std::shared_ptr<const Cloud> lidarCloud() {
  pcl::PointCloud<pcl::PointXYZI> typed;
  for (int i = 0; i < 500; ++i) typed.push_back(pcl::PointXYZI(0.01f * (i % 20), 0.01f * (i / 20), 1.f, float(i)));
  auto points = apex_nodes::toBlob(typed);
  pcl::PCLPointField ring;
  ring.name = "ring", ring.offset = points->point_step, ring.datatype = pcl::PCLPointField::UINT16, ring.count = 1;
  auto wide = std::make_shared<pcl::PCLPointCloud2>(*points);
  wide->fields.push_back(ring);
  wide->point_step = points->point_step + 4;
  wide->row_step = wide->point_step * wide->width;
  wide->data.assign(std::size_t(wide->row_step), 0);
  for (std::size_t i = 0; i < typed.size(); ++i) {
    std::memcpy(&wide->data[i * wide->point_step], &points->data[i * points->point_step], points->point_step);
    const std::uint16_t r = std::uint16_t(i % 16);
    std::memcpy(&wide->data[i * wide->point_step + ring.offset], &r, sizeof r);
  }
  auto c = std::make_shared<Cloud>();
  c->header = lidarHeader();
  c->points = wide;
  return c;
}

TEST(CloudNodes, FieldsNoPointTypeHasPassThroughFilters) {
  NodeHarness h("apex_nodes/PassThrough", {"cloud"}, "cloud");
  h.set("field", "x"), h.set("limits", "[0.0, 0.095]");  // x = 0.00 .. 0.09: half of each row
  const Cloud& got = out(h.run(lidarCloud()));
  EXPECT_EQ(apex_nodes::fieldNames(*got.points), "x, y, z, intensity, ring");
  ASSERT_EQ(apex_nodes::pointCount(got), 250u);
  const auto intensity = apex_nodes::typedPoints<pcl::PointXYZI>(got);
  for (std::size_t k = 0; k < intensity.size(); ++k) {
    const std::size_t i = (k / 10) * 20 + k % 10;  // the input point it is
    ASSERT_EQ(intensity[k].intensity, float(i)) << k;
    std::uint16_t ring = 0;
    std::memcpy(&ring, &got.points->data[k * got.points->point_step + got.points->fields.back().offset], sizeof ring);
    ASSERT_EQ(ring, i % 16) << k;
  }
}

TEST(CloudNodes, VoxelGridAveragesFieldsNoPointTypeHasAsPclDoes) {
  NodeHarness h("apex_nodes/VoxelGrid", {"cloud"}, "cloud");
  h.set("leaf_size", "0.05");
  pcl::VoxelGrid<pcl::PCLPointCloud2> f;
  f.setInputCloud(lidarCloud()->points);
  f.setLeafSize(0.05f, 0.05f, 0.05f);
  pcl::PCLPointCloud2 want;
  f.filter(want);
  const Cloud& got = out(h.run(lidarCloud()));
  EXPECT_EQ(apex_nodes::fieldNames(*got.points), apex_nodes::fieldNames(want));
  EXPECT_EQ(got.points->width, want.width);
  EXPECT_EQ(got.points->data, want.data);
}

TEST(CloudNodes, ANodeNeedingAFieldTheCloudLacksNamesIt) {
  NodeHarness h("apex_nodes/VoxelGrid", {"cloud"}, "cloud");
  auto flat = std::make_shared<pcl::PCLPointCloud2>(*cloud()->points);
  flat->fields.erase(flat->fields.begin() + 2);  // no z
  auto c = std::make_shared<Cloud>();
  c->header = lidarHeader();
  c->points = flat;
  EXPECT_TRUE(h.run(std::shared_ptr<const Cloud>(c)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("point cloud 2000x1 on frame 'lidar' has no field 'z' (its fields: x, y, rgb)"));
}

/** A floor (y = 0.5) with scattered points above it: a plane and two blobs. */
std::shared_ptr<const Cloud> scene() {
  auto points = std::make_shared<Xyz>();
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) points->push_back(pcl::PointXYZ(0.05f * i, 0.5f, 0.05f * j));
  for (int i = 0; i < 100; ++i) {
    points->push_back(pcl::PointXYZ(0.2f + 0.001f * (i % 10), 0.1f + 0.001f * (i / 10), 0.2f));
    points->push_back(pcl::PointXYZ(1.5f + 0.001f * (i % 10), 0.1f + 0.001f * (i / 10), 1.5f));
  }
  return apex_nodes::makeCloud(lidarHeader(), *points);
}

Xyz xyzScene() { return apex_nodes::typedPoints<pcl::PointXYZ>(*scene()); }

TEST(CloudNodes, PlaneSegmentationSplitsThePlane) {
  NodeHarness h("apex_nodes/PlaneSegmentation", {"cloud"}, "inliers");
  EXPECT_EQ(apex_nodes::pointCount(out(h.run(scene()))), 1600u);  // the whole floor
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
  auto points = std::make_shared<Xyz>(xyzScene());
  auto tree = std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
  tree->setInputCloud(points);
  std::vector<pcl::PointIndices> want;
  pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
  ec.setClusterTolerance(0.02);
  ec.setMinClusterSize(50);
  ec.setMaxClusterSize(1000000);
  ec.setSearchMethod(tree);
  ec.setInputCloud(points);
  ec.extract(want);
  ASSERT_EQ(clusters->clusters.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_EQ(clusters->clusters[i]->width, want[i].indices.size());
}

TEST(CloudNodes, ClustersBecomeOneCloudLabelledByCluster) {
  NodeHarness h("apex_nodes/EuclideanClustering", {"cloud"}, "clusters");
  h.set("tolerance", "0.02");
  const auto clusters = h.run(scene()).as<apex_nodes::Clusters>();
  ASSERT_TRUE(clusters);
  ASSERT_EQ(clusters->clusters.size(), 2u);  // the two blobs (the floor's points are 5 cm apart)
  NodeHarness join("apex_nodes/ClustersToCloud", {"clusters"}, "cloud");
  const Cloud& got = out(join.run(clusters));
  EXPECT_EQ(apex_nodes::fieldNames(*got.points), "x, y, z, label");
  const auto labelled = apex_nodes::typedPoints<pcl::PointXYZL>(got);
  std::size_t k = 0;
  for (std::uint32_t c = 0; c < clusters->clusters.size(); ++c) {
    const auto cluster = apex_nodes::typedPoints<pcl::PointXYZ>(*apex_nodes::cloudResult(got, clusters->clusters[c]));
    for (const auto& p : cluster) {
      ASSERT_LT(k, labelled.size());
      EXPECT_EQ(labelled[k].label, c) << k;
      EXPECT_EQ(labelled[k].x, p.x) << k;
      ++k;
    }
  }
  EXPECT_EQ(k, labelled.size());
}

TEST(CloudNodes, LaserScanToCloudKeepsValidRanges) {
  NodeHarness h("apex_nodes/LaserScanToCloud", {"scan"}, "cloud");
  auto scan = std::make_shared<sensor_msgs::LaserScan>();
  scan->header.frame_id = "lidar";
  scan->angle_min = 0;
  scan->angle_increment = M_PI / 2;
  scan->range_min = 0.1f, scan->range_max = 10.f;
  scan->ranges = {1.f, std::nanf(""), 2.f, 50.f};
  scan->intensities = {10.f, 20.f, 30.f, 40.f};
  const auto& c = *h.run(std::shared_ptr<const sensor_msgs::LaserScan>(scan)).as<Cloud>();
  EXPECT_EQ(apex_nodes::fieldNames(*c.points), "x, y, z, intensity");
  const auto points = apex_nodes::typedPoints<pcl::PointXYZI>(c);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_NEAR(points[0].x, 1.0, 1e-6);
  EXPECT_NEAR(points[1].x, -2.0, 1e-6);  // 180 degrees
  EXPECT_EQ(points[1].intensity, 30.f);
  scan->intensities.clear();
  EXPECT_EQ(apex_nodes::fieldNames(*h.run(std::shared_ptr<const sensor_msgs::LaserScan>(scan)).as<Cloud>()->points), "x, y, z");
  scan->ranges = {std::nanf(""), std::nanf("")};
  EXPECT_TRUE(h.run(std::shared_ptr<const sensor_msgs::LaserScan>(scan)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("has none within"));
}

TEST(CloudNodes, ANanOnlyCloudIsAnError) {
  NodeHarness h("apex_nodes/PassThrough", {"cloud"}, "cloud");
  Xyz points;
  points.push_back(pcl::PointXYZ(std::nanf(""), 0, 0));
  EXPECT_TRUE(h.run(std::shared_ptr<const Cloud>(apex_nodes::makeCloud(lidarHeader(), points))).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("none of them finite"));
}

TEST(CloudNodes, AnEmptyCloudIsAnError) {
  NodeHarness h("apex_nodes/VoxelGrid", {"cloud"}, "cloud");
  EXPECT_TRUE(h.run(std::shared_ptr<const Cloud>(apex_nodes::makeCloud(lidarHeader(), Xyz()))).isNothing());
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
  Rgb want;
  pcl::transformPointCloud(colouredPoints(), want, m);
  const Rgb moved = apex_nodes::typedPoints<pcl::PointXYZRGB>(got);
  ASSERT_EQ(moved.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_NEAR(moved[i].x, want[i].x, 1e-5);
    ASSERT_NEAR(moved[i].y, want[i].y, 1e-5);
    ASSERT_NEAR(moved[i].z, want[i].z, 1e-5);
    ASSERT_EQ(moved[i].rgba, want[i].rgba);
  }
  t->child_frame_id = "camera";
  EXPECT_TRUE(h.run({Message::share<Cloud>(cloud()), Message::share<geometry_msgs::TransformStamped>(t)}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("the transform maps frame 'camera', the cloud is in 'lidar'"));
}

}  // namespace
