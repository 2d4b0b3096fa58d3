// MovingLeastSquares and FPFHEstimation against the same PCL calls made directly, on the real aloe
// cloud (apex_test/aloe_cloud.hpp): the same library code on the same floats, so point by point
// equal, NaN where PCL gives NaN.
#include <gmock/gmock.h>
#include <pcl/features/fpfh.h>
#include <pcl/features/normal_3d.h>
#include <pcl/surface/mls.h>

#include <cmath>
#include <limits>

#include "apex_nodes/cloud.hpp"
#include "apex_test/aloe_cloud.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using apex_nodes::Cloud;
using ::testing::HasSubstr;
using Smoothed = pcl::PointCloud<pcl::PointNormal>;
using Histograms = pcl::PointCloud<pcl::FPFHSignature33>;

namespace {

/** aloe with a NaN point before every 1000th of its points: the nodes leave them out. */
std::shared_ptr<const Cloud> cloudWithNans() {
  pcl::PointCloud<pcl::PointXYZRGB> points;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t i = 0; i < aloe().size(); ++i) {
    if (i % 1000 == 0) {
      pcl::PointXYZRGB bad = aloe()[i];
      bad.x = bad.y = bad.z = nan;
      points.push_back(bad);
    }
    points.push_back(aloe()[i]);
  }
  points.is_dense = false;
  return apex_nodes::makeCloud(aloeHeader(), points);
}

const Cloud& out(const Message& m) {
  auto c = m.as<Cloud>();
  if (!c) throw std::runtime_error("expected a cloud, got " + m.typeName());
  EXPECT_EQ(c->header, aloeHeader());
  return *c;
}

/** Equal floats, or both NaN. */
bool same(float a, float b) { return a == b || (std::isnan(a) && std::isnan(b)); }

/** PCL's MovingLeastSquares on aloe's x, y, z, one thread; `from`: the input point each came from. */
Smoothed pclSmoothed(double radius, int order, bool normals, pcl::Indices* from = nullptr) {
  pcl::MovingLeastSquares<pcl::PointXYZ, pcl::PointNormal> direct;
  direct.setInputCloud(aloeXyz());
  direct.setSearchRadius(radius), direct.setPolynomialOrder(order), direct.setComputeNormals(normals);
  direct.setNumberOfThreads(1);
  direct.setCacheMLSResults(true);
  Smoothed want;
  direct.process(want);
  // a point whose fit failed (its neighbours on a line) has no normal: PCL leaves it unset, the node NaN
  const auto& fits = direct.getMLSResults();
  const auto& came = direct.getCorrespondingIndices()->indices;
  for (std::size_t i = 0; i < want.size(); ++i)
    if (normals && !fits.at(came[i]).valid) want[i].normal_x = want[i].normal_y = want[i].normal_z = want[i].curvature = NAN;
  if (from) *from = came;
  return want;
}

/** x, y, z, and the normals and curvature if `normals`, point by point. */
void expectSame(const Cloud& got, const Smoothed& want, bool normals) {
  const auto xyz = apex_nodes::typedPoints<pcl::PointXYZ>(got);
  ASSERT_EQ(xyz.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i)
    ASSERT_TRUE(same(xyz[i].x, want[i].x) && same(xyz[i].y, want[i].y) && same(xyz[i].z, want[i].z)) << i;
  if (!normals) return;
  const auto n = apex_nodes::typedPoints<pcl::Normal>(got);
  ASSERT_EQ(n.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i)
    ASSERT_TRUE(same(n[i].normal_x, want[i].normal_x) && same(n[i].normal_y, want[i].normal_y) &&
                same(n[i].normal_z, want[i].normal_z) && same(n[i].curvature, want[i].curvature))
        << i;
}

TEST(CloudSmoothing, MovingLeastSquaresIsPclsSmoothedCloudWithNormals) {
  NodeHarness h("apex_nodes/MovingLeastSquares", {"cloud"}, "cloud");
  h.set("search_radius", "0.05"), h.set("polynomial_order", "2"), h.set("compute_normals", "true");
  pcl::Indices from;
  const Smoothed want = pclSmoothed(0.05, 2, true, &from);
  ASSERT_GT(want.size(), aloe().size() / 2);
  ASSERT_EQ(from.size(), want.size());
  std::size_t moved = 0;  // against the input point each came from
  for (std::size_t i = 0; i < want.size(); ++i) moved += want[i].z != aloe()[from[i]].z;
  EXPECT_GT(moved, want.size() / 10) << "a smoothing that moves nothing proves little";
  const Cloud& got = out(h.run(aloeCloud()));
  EXPECT_EQ(apex_nodes::fieldNames(*got.points), "x, y, z, normal_x, normal_y, normal_z, curvature");
  expectSame(got, want, true);
  // NaN points are left out before PCL sees them: the same points come out
  expectSame(out(h.run(cloudWithNans())), want, true);
}

TEST(CloudSmoothing, MovingLeastSquaresWithoutNormalsSendsXyzOnly) {
  NodeHarness h("apex_nodes/MovingLeastSquares", {"cloud"}, "cloud");
  h.set("search_radius", "0.04"), h.set("polynomial_order", "1"), h.set("compute_normals", "false");
  const Smoothed want = pclSmoothed(0.04, 1, false);
  ASSERT_GT(want.size(), aloe().size() / 2);
  const Cloud& got = out(h.run(aloeCloud()));
  EXPECT_EQ(apex_nodes::fieldNames(*got.points), "x, y, z");
  expectSame(got, want, false);
}

TEST(CloudSmoothing, MovingLeastSquaresWithNoNeighboursSaysSo) {
  NodeHarness h("apex_nodes/MovingLeastSquares", {"cloud"}, "cloud");
  h.set("search_radius", "0.001");
  EXPECT_TRUE(h.run(aloeCloud()).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("has 2 others within search_radius 0.001"));
}

/** PCL's NormalEstimation (radius or k) then FPFHEstimation on aloe's x, y, z. */
Histograms pclHistograms(double normal_radius, int normal_k, double feature_radius) {
  const auto xyz = aloeXyz();
  auto normals = std::make_shared<pcl::PointCloud<pcl::Normal>>();
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> estimation;
  estimation.setInputCloud(xyz);
  if (normal_k > 0) estimation.setKSearch(normal_k);
  else estimation.setRadiusSearch(normal_radius);
  estimation.compute(*normals);
  pcl::FPFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::FPFHSignature33> direct;
  direct.setInputCloud(xyz), direct.setInputNormals(normals), direct.setRadiusSearch(feature_radius);
  Histograms want;
  direct.compute(want);
  return want;
}

/** The node's cloud: aloe's x, y, z with PCL's histogram as the field fpfh, bin by bin. */
void expectHistograms(const Cloud& got, const Histograms& want) {
  EXPECT_EQ(apex_nodes::fieldNames(*got.points), "x, y, z, fpfh");
  const auto xyz = apex_nodes::typedPoints<pcl::PointXYZ>(got);
  const auto histograms = apex_nodes::typedPoints<pcl::FPFHSignature33>(got);
  ASSERT_EQ(xyz.size(), aloe().size());
  ASSERT_EQ(histograms.size(), want.size());
  ASSERT_EQ(want.size(), aloe().size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(xyz[i].x, aloe()[i].x) << i;
    ASSERT_EQ(xyz[i].y, aloe()[i].y) << i;
    ASSERT_EQ(xyz[i].z, aloe()[i].z) << i;
    for (int b = 0; b < 33; ++b)
      ASSERT_TRUE(same(histograms[i].histogram[b], want[i].histogram[b]))
          << "point " << i << " bin " << b << ": " << histograms[i].histogram[b] << " vs PCL's " << want[i].histogram[b];
  }
}

TEST(CloudSmoothing, FPFHEstimationIsPclsHistogramsBesideEachPoint) {
  NodeHarness h("apex_nodes/FPFHEstimation", {"cloud"}, "features");
  h.set("normal_search", "radius"), h.set("normal_radius", "0.05"), h.set("feature_radius", "0.08");
  const Histograms want = pclHistograms(0.05, 0, 0.08);
  std::size_t described = 0;  // finite histograms with some weight: the comparison is of real features
  for (const auto& f : want) {
    float sum = 0;
    for (float bin : f.histogram) sum += bin;
    described += std::isfinite(sum) && sum > 0;
  }
  EXPECT_GT(described, want.size() / 2);
  expectHistograms(out(h.run(aloeCloud())), want);
  expectHistograms(out(h.run(cloudWithNans())), want);  // the NaN points left out
}

TEST(CloudSmoothing, FPFHEstimationWithKNearestNormalsIsPcls) {
  NodeHarness h("apex_nodes/FPFHEstimation", {"cloud"}, "features");
  h.set("normal_search", "k"), h.set("normal_k", "15"), h.set("feature_radius", "0.06");
  expectHistograms(out(h.run(aloeCloud())), pclHistograms(0, 15, 0.06));
}

}  // namespace
