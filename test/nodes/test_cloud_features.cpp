// Point-cloud sampling, keypoints, region growing, conditional clustering and the concave hull
// against the same PCL call made directly, on a real cloud: the Middlebury aloe pair's ground-truth
// disparity (opencv-doc's aloeGT.png) made into points, coloured from aloeL.jpg.
#include <gmock/gmock.h>
#include <pcl/features/normal_3d.h>
#include <pcl/filters/random_sample.h>
#include <pcl/filters/uniform_sampling.h>
#include <pcl/keypoints/harris_3d.h>
#include <pcl/keypoints/iss_3d.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/conditional_euclidean_clustering.h>
#include <pcl/segmentation/region_growing.h>
#include <pcl/segmentation/region_growing_rgb.h>
#include <pcl/surface/concave_hull.h>

#include <algorithm>

#include "apex_nodes/cloud.hpp"
#include "apex_test/node_harness.hpp"
#include "apex_test/aloe_cloud.hpp"

using namespace apex_test;
using apex_nodes::Cloud;
using apex_nodes::Clusters;
using ::testing::HasSubstr;
using Rgb = pcl::PointCloud<pcl::PointXYZRGB>;
using Xyz = pcl::PointCloud<pcl::PointXYZ>;

namespace {

std_msgs::Header header() { return aloeHeader(); }
std::shared_ptr<const Cloud> cloud() { return aloeCloud(); }
std::shared_ptr<const Xyz> xyz() { return aloeXyz(); }

const Cloud& out(const Message& m) {
  auto c = m.as<Cloud>();
  if (!c) throw std::runtime_error("expected a cloud, got " + m.typeName());
  EXPECT_EQ(c->header, header());
  return *c;
}

Rgb colours(const Message& m) { return apex_nodes::typedPoints<pcl::PointXYZRGB>(out(m)); }

/** aloe's points at `indices`. */
Rgb at(const pcl::Indices& indices) {
  Rgb out;
  for (auto i : indices) out.push_back(aloe()[i]);
  return out;
}

void expectSame(const Rgb& got, const Rgb& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(got[i].x, want[i].x) << i;
    ASSERT_EQ(got[i].y, want[i].y) << i;
    ASSERT_EQ(got[i].z, want[i].z) << i;
    ASSERT_EQ(got[i].rgba, want[i].rgba) << i;
  }
}

/** The clusters a node sent against PCL's, largest first (ties in PCL's order), point by point. */
void expectSameClusters(const Message& m, std::vector<pcl::PointIndices> want) {
  std::stable_sort(want.begin(), want.end(), [](const auto& a, const auto& b) { return a.indices.size() > b.indices.size(); });
  auto got = m.as<Clusters>();
  ASSERT_TRUE(got) << m.typeName();
  EXPECT_EQ(got->header, header());
  ASSERT_EQ(got->clusters.size(), want.size());
  for (std::size_t k = 0; k < want.size(); ++k) {
    Rgb points;
    pcl::fromPCLPointCloud2(*got->clusters[k], points);
    expectSame(points, at(want[k].indices));
  }
}

TEST(CloudFeatures, TheAloeCloudIsReal) {
  ASSERT_GT(aloe().size(), 10000u);
  ASSERT_LT(aloe().size(), 25000u);
}

TEST(CloudFeatures, RandomSampleKeepsPclsPointsWhole) {
  NodeHarness h("apex_nodes/RandomSample", {"cloud"}, "cloud");
  h.set("sample", "500"), h.set("seed", "7");
  pcl::RandomSample<pcl::PointXYZRGB> direct;
  direct.setInputCloud(std::make_shared<Rgb>(aloe()));
  direct.setSample(500), direct.setSeed(7);
  Rgb want;
  direct.filter(want);
  ASSERT_EQ(want.size(), 500u);
  expectSame(colours(h.run(cloud())), want);
}

TEST(CloudFeatures, UniformSamplingKeepsPclsPointsInTheInputsOrder) {
  NodeHarness h("apex_nodes/UniformSampling", {"cloud"}, "cloud");
  h.set("radius", "0.1");
  pcl::UniformSampling<pcl::PointXYZ> direct(true);
  direct.setInputCloud(xyz());
  direct.setRadiusSearch(0.1);
  Xyz kept;
  direct.filter(kept);
  pcl::Indices dropped = *direct.getRemovedIndices();
  std::sort(dropped.begin(), dropped.end());
  const Rgb want = at(apex_nodes::complement(dropped, aloe().size()));
  ASSERT_EQ(want.size(), kept.size());
  ASSERT_GT(want.size(), 200u);
  ASSERT_LT(want.size(), aloe().size() / 4);
  expectSame(colours(h.run(cloud())), want);
}

TEST(CloudFeatures, ISSKeypointsArePclsPointsWhole) {
  NodeHarness h("apex_nodes/ISSKeypoints", {"cloud"}, "keypoints");
  h.set("salient_radius", "0.12"), h.set("non_max_radius", "0.08");
  pcl::ISSKeypoint3D<pcl::PointXYZ, pcl::PointXYZ> direct;
  direct.setSearchMethod(std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
  direct.setSalientRadius(0.12), direct.setNonMaxRadius(0.08);
  direct.setThreshold21(0.975), direct.setThreshold32(0.975), direct.setMinNeighbors(5);
  direct.setNumberOfThreads(1);
  direct.setInputCloud(xyz());
  Xyz found;
  direct.compute(found);
  const auto& indices = direct.getKeypointsIndices()->indices;
  ASSERT_GT(indices.size(), 5u);
  expectSame(colours(h.run(cloud())), at(indices));
}

TEST(CloudFeatures, HarrisKeypoints3DArePclsWithTheirResponse) {
  NodeHarness h("apex_nodes/HarrisKeypoints3D", {"cloud"}, "keypoints");
  h.set("method", "tomasi"), h.set("radius", "0.1"), h.set("threshold", "0.0001");
  using Harris = pcl::HarrisKeypoint3D<pcl::PointXYZ, pcl::PointXYZI>;
  Harris direct(Harris::TOMASI, 0.1f, 0.0001f);
  direct.setNonMaxSupression(true), direct.setRefine(true), direct.setNumberOfThreads(1);
  direct.setSearchMethod(std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
  direct.setInputCloud(xyz());
  pcl::PointCloud<pcl::PointXYZI> want;
  direct.compute(want);
  ASSERT_GT(want.size(), 5u);
  const auto got = apex_nodes::typedPoints<pcl::PointXYZI>(out(h.run(cloud())));
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(got[i].x, want[i].x) << i;
    EXPECT_EQ(got[i].z, want[i].z) << i;
    EXPECT_EQ(got[i].intensity, want[i].intensity) << i;
  }
}

TEST(CloudFeatures, RegionGrowingGivesPclsRegionsLargestFirst) {
  NodeHarness h("apex_nodes/RegionGrowing", {"cloud"}, "clusters");
  auto tree = std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
  auto normals = std::make_shared<pcl::PointCloud<pcl::Normal>>();
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> estimate;
  estimate.setSearchMethod(tree), estimate.setInputCloud(xyz()), estimate.setKSearch(30);
  estimate.compute(*normals);
  pcl::RegionGrowing<pcl::PointXYZ, pcl::Normal> direct;
  direct.setMinClusterSize(50), direct.setMaxClusterSize(1000000);
  direct.setSearchMethod(tree), direct.setNumberOfNeighbours(30);
  direct.setInputCloud(xyz()), direct.setInputNormals(normals);
  direct.setSmoothnessThreshold(3.0 / 180.0 * M_PI), direct.setCurvatureThreshold(1.0);
  std::vector<pcl::PointIndices> want;
  direct.extract(want);
  ASSERT_GT(want.size(), 1u);
  expectSameClusters(h.run(cloud()), want);
}

TEST(CloudFeatures, RegionGrowingRGBGivesPclsRegionsAndNeedsColour) {
  NodeHarness h("apex_nodes/RegionGrowingRGB", {"cloud"}, "clusters");
  h.set("distance", "0.05"), h.set("point_colour", "6"), h.set("region_colour", "5"), h.set("min_size", "30");
  pcl::RegionGrowingRGB<pcl::PointXYZRGB> direct;
  direct.setInputCloud(std::make_shared<Rgb>(aloe()));
  direct.setSearchMethod(std::make_shared<pcl::search::KdTree<pcl::PointXYZRGB>>());
  direct.setDistanceThreshold(0.05f), direct.setPointColorThreshold(6), direct.setRegionColorThreshold(5);
  direct.setMinClusterSize(30), direct.setMaxClusterSize(1000000);
  std::vector<pcl::PointIndices> want;
  direct.extract(want);
  ASSERT_GT(want.size(), 1u);
  expectSameClusters(h.run(cloud()), want);
  h.run(std::shared_ptr<const Cloud>(apex_nodes::makeCloud(header(), *xyz())));
  EXPECT_THAT(h.error(), HasSubstr("rgb"));
}

TEST(CloudFeatures, ConditionalEuclideanClusteringJoinsCloseAlikePointsAsPclDoes) {
  NodeHarness h("apex_nodes/ConditionalEuclideanClustering", {"cloud"}, "clusters");
  h.set("tolerance", "0.04"), h.set("colour_distance", "20"), h.set("min_size", "30");
  pcl::ConditionalEuclideanClustering<pcl::PointXYZRGB> direct;
  direct.setInputCloud(std::make_shared<Rgb>(aloe()));
  direct.setConditionFunction(std::function<bool(const pcl::PointXYZRGB&, const pcl::PointXYZRGB&, float)>(
      [](const pcl::PointXYZRGB& a, const pcl::PointXYZRGB& b, float) {
        const float r = float(a.r) - b.r, g = float(a.g) - b.g, bl = float(a.b) - b.b;
        return r * r + g * g + bl * bl <= 20.0f * 20.0f;
      }));
  direct.setClusterTolerance(0.04f), direct.setMinClusterSize(30), direct.setMaxClusterSize(1000000);
  pcl::IndicesClusters want;
  direct.segment(want);
  ASSERT_GT(want.size(), 1u);
  expectSameClusters(h.run(cloud()), want);
}

TEST(CloudFeatures, ConcaveHullIsPclsOutlineWhole) {
  NodeHarness h("apex_nodes/ConcaveHull", {"cloud"}, "hull");
  h.set("alpha", "0.1"), h.set("dimension", "2");
  pcl::ConcaveHull<pcl::PointXYZ> direct;
  direct.setInputCloud(xyz()), direct.setAlpha(0.1), direct.setDimension(2), direct.setKeepInformation(true);
  Xyz outline;
  std::vector<pcl::Vertices> polygons;
  direct.reconstruct(outline, polygons);
  pcl::PointIndices indices;
  direct.getHullPointIndices(indices);
  ASSERT_GT(indices.indices.size(), 20u);
  expectSame(colours(h.run(cloud())), at(indices.indices));
}

}  // namespace
