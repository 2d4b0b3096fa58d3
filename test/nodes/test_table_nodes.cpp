// The "objects on a table" chain — NormalEstimation, SACSegmentation, ProjectInliers, ConvexHull,
// ExtractPolygonalPrism — each against the same PCL call made directly on the same points: the
// same indices and values, and every field of the points kept (their colour says what they are).
#include <gmock/gmock.h>
#include <pcl/features/normal_3d.h>
#include <pcl/filters/project_inliers.h>
#include <pcl/segmentation/extract_polygonal_prism_data.h>
#include <pcl/segmentation/sac_segmentation.h>
#include <pcl/surface/convex_hull.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

#include "apex_nodes/cloud.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using apex_nodes::Cloud;
using ::testing::HasSubstr;
using Rgb = pcl::PointCloud<pcl::PointXYZRGB>;
using Xyz = pcl::PointCloud<pcl::PointXYZ>;
using CloudPtr = std::shared_ptr<const Cloud>;

namespace {

std_msgs::Header header() {
  std_msgs::Header h;
  h.frame_id = "base_link";
  h.stamp = ros::Time(7, 250000001);
  return h;
}

// What each point of the scene is, by its colour.
const std::uint32_t kTable = 0x808080, kRedBox = 0xff0000, kBlueBox = 0x0000ff, kBeside = 0x00ff00, kBelow = 0xffffff;
const std::size_t kTablePoints = 61 * 41, kBoxPoints = 6 * 6 * 8 + 7 * 5 * 6, kScenePoints = kTablePoints + kBoxPoints + 36 + 45;

pcl::PointXYZRGB point(float x, float y, float z, std::uint32_t rgb) {
  pcl::PointXYZRGB p(std::uint8_t(rgb >> 16), std::uint8_t(rgb >> 8), std::uint8_t(rgb));
  p.x = x, p.y = y, p.z = z;
  return p;
}
std::uint32_t colour(const pcl::PointXYZRGB& p) { return p.rgba & 0xffffffu; }

/** A table top (z = 0.7, 1.2 x 0.8 m, a point every 2 cm, ±1 mm of noise from a fixed seed) with
 *  two boxes of points on it (from 2 cm above it), points beside it above its height and a few
 *  below it: in that order. */
Rgb scenePoints() {
  Rgb points;
  std::mt19937 random(32);
  std::uniform_real_distribution<float> noise(-0.001f, 0.001f);
  for (int i = 0; i <= 60; ++i)
    for (int j = 0; j <= 40; ++j) points.push_back(point(0.02f * i, 0.02f * j, 0.7f + noise(random), kTable));
  for (int i = 0; i < 6; ++i)  // 10 x 10 x 14 cm
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 8; ++k) points.push_back(point(0.25f + 0.02f * i, 0.25f + 0.02f * j, 0.72f + 0.02f * k, kRedBox));
  for (int i = 0; i < 7; ++i)  // 12 x 8 x 10 cm
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 6; ++k) points.push_back(point(0.7f + 0.02f * i, 0.4f + 0.02f * j, 0.72f + 0.02f * k, kBlueBox));
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) points.push_back(point(1.4f + 0.02f * i, 0.3f + 0.02f * j, 0.8f, kBeside));
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 5; ++j) points.push_back(point(0.2f + 0.1f * i, 0.2f + 0.1f * j, 0.3f, kBelow));
  return points;
}

const CloudPtr& scene() {
  static const CloudPtr s = apex_nodes::makeCloud(header(), scenePoints());
  return s;
}
Xyz xyz(const Cloud& c) { return apex_nodes::typedPoints<pcl::PointXYZ>(c); }
Message share(const CloudPtr& c) { return Message::share<Cloud>(c); }

CloudPtr cloudOf(const Message& m) {
  auto c = m.as<Cloud>();
  if (!c) throw std::runtime_error("expected a cloud, got " + m.typeName());
  EXPECT_EQ(c->header, header());
  return c;
}

/** `got` is the points of `from` at `indices`, whole (every field, byte for byte), in that order. */
void expectSelected(const Cloud& got, const Cloud& from, const pcl::Indices& indices) {
  ASSERT_FALSE(indices.empty());
  EXPECT_EQ(apex_nodes::fieldNames(*got.points), apex_nodes::fieldNames(*from.points));
  ASSERT_EQ(apex_nodes::pointCount(got), indices.size());
  EXPECT_TRUE(got.points->data == apex_nodes::selectPoints(*from.points, indices)->data);
}

std::size_t countColour(const Cloud& c, std::uint32_t rgb) {
  const Rgb points = apex_nodes::typedPoints<pcl::PointXYZRGB>(c);
  return std::size_t(std::count_if(points.begin(), points.end(), [&](const auto& p) { return colour(p) == rgb; }));
}

/** PCL's (non-OMP) NormalEstimation on the x, y, z of `c`. */
template <class Configure>
pcl::PointCloud<pcl::Normal> pclNormals(const Cloud& c, Configure configure) {
  pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> estimation;
  estimation.setInputCloud(std::make_shared<Xyz>(xyz(c)));
  configure(estimation);
  pcl::PointCloud<pcl::Normal> out;
  estimation.compute(out);
  return out;
}

bool same(float a, float b) { return a == b || (std::isnan(a) && std::isnan(b)); }

/** `got` is the scene, every point with its colour, and `want`'s normals and curvature. */
void expectSceneWithNormals(const Cloud& got, const pcl::PointCloud<pcl::Normal>& want) {
  EXPECT_EQ(apex_nodes::fieldNames(*got.points), "x, y, z, rgb, normal_x, normal_y, normal_z, curvature");
  const auto points = apex_nodes::typedPoints<pcl::PointXYZRGBNormal>(got);
  const Rgb input = scenePoints();
  ASSERT_EQ(points.size(), want.size());
  ASSERT_EQ(points.size(), input.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    ASSERT_TRUE(points[i].x == input[i].x && points[i].y == input[i].y && points[i].z == input[i].z) << i;
    ASSERT_EQ(points[i].rgba, input[i].rgba) << i;
    ASSERT_TRUE(same(points[i].normal_x, want[i].normal_x) && same(points[i].normal_y, want[i].normal_y) &&
                same(points[i].normal_z, want[i].normal_z) && same(points[i].curvature, want[i].curvature))
        << i;
  }
}

TEST(TableNodes, NormalEstimationAddsPclsNormalsAndKeepsEveryField) {
  NodeHarness h("apex_nodes/NormalEstimation", {"cloud"}, "cloud");
  h.set("radius", "0.05"), h.set("viewpoint", "[0, 0, 2]");
  const auto want = pclNormals(*scene(), [](auto& e) { e.setRadiusSearch(0.05), e.setViewPoint(0, 0, 2); });
  EXPECT_TRUE(std::isnan(want.back().normal_x));  // the points below: too far apart for 5 cm
  EXPECT_NEAR(want[0].normal_z, 1.0, 0.05);  // the table's: up, to the viewpoint
  const CloudPtr with_normals = cloudOf(h.run(scene()));
  expectSceneWithNormals(*with_normals, want);

  // The k nearest; a cloud with normals already gets new ones in their place.
  h.set("search", "k"), h.set("k", "12");
  const CloudPtr again = cloudOf(h.run(with_normals));
  EXPECT_EQ(again->points->point_step, with_normals->points->point_step);
  expectSceneWithNormals(*again, pclNormals(*scene(), [](auto& e) { e.setKSearch(12), e.setViewPoint(0, 0, 2); }));
}

struct Fit {
  pcl::PointIndices inliers;
  pcl::ModelCoefficients coefficients;
};

/** PCL's segmentation `seg` set as SACSegmentation sets it (its defaults but for these). */
template <class Segmentation>
Fit pclFit(Segmentation& seg, const Cloud& c, int model, double threshold, double min_radius = 0, double max_radius = 10) {
  seg.setOptimizeCoefficients(true);
  seg.setModelType(model);
  seg.setMethodType(pcl::SAC_RANSAC);
  seg.setDistanceThreshold(threshold);
  seg.setMaxIterations(200);
  seg.setRadiusLimits(min_radius, max_radius);
  seg.setAxis(Eigen::Vector3f::UnitZ());
  seg.setEpsAngle(0);
  seg.setInputCloud(std::make_shared<Xyz>(xyz(c)));
  Fit out;
  seg.segment(out.inliers, out.coefficients);
  return out;
}

/** SACSegmentation set by `params` on `c`: its inliers as PCL's `want` gives them, its outliers the
 *  rest, its coefficients PCL's. */
void expectFit(const CloudPtr& c, const std::vector<std::pair<std::string, std::string>>& params, const Fit& want) {
  for (const char* output : {"inliers", "outliers", "coefficients", "count"}) {
    NodeHarness h("apex_nodes/SACSegmentation", {"cloud"}, output);
    for (const auto& [name, value] : params) h.set(name, value);
    const Message got = h.run({share(c)});
    ASSERT_FALSE(got.isNothing()) << h.error();
    const std::string o = output;
    if (o == "inliers") expectSelected(*cloudOf(got), *c, want.inliers.indices);
    if (o == "outliers")
      expectSelected(*cloudOf(got), *c, apex_nodes::complement(want.inliers.indices, apex_nodes::pointCount(*c)));
    if (o == "coefficients") {
      EXPECT_EQ(*got.as<std::vector<double>>(),
                std::vector<double>(want.coefficients.values.begin(), want.coefficients.values.end()));
    }
    if (o == "count") {
      EXPECT_EQ(*got.as<int>(), int(want.inliers.indices.size()));
    }
  }
}

TEST(TableNodes, SACSegmentationsPlaneIsPclsAndPlaneSegmentations) {
  pcl::SACSegmentation<pcl::PointXYZ> seg;
  const Fit want = pclFit(seg, *scene(), pcl::SACMODEL_PLANE, 0.01);
  expectFit(scene(), {{"distance_threshold", "0.01"}}, want);
  NodeHarness plane("apex_nodes/PlaneSegmentation", {"cloud"}, "inliers");
  plane.set("distance_threshold", "0.01");
  const CloudPtr table = cloudOf(plane.run(scene()));
  expectSelected(*table, *scene(), want.inliers.indices);
  EXPECT_EQ(countColour(*table, kTable), kTablePoints);  // the whole table and nothing else
  EXPECT_EQ(apex_nodes::pointCount(*table), kTablePoints);
}

TEST(TableNodes, SACSegmentationFitsASphereAsPclDoes) {
  Rgb points;
  const Eigen::Vector3f centre(0.4f, 0.2f, 0.9f);
  for (int i = 0; i < 300; ++i) {  // a Fibonacci sphere, r = 8 cm
    const float z = 1.f - 2.f * (float(i) + 0.5f) / 300.f, r = std::sqrt(1.f - z * z), phi = 2.39996323f * float(i);
    const Eigen::Vector3f p = centre + 0.08f * Eigen::Vector3f(r * std::cos(phi), r * std::sin(phi), z);
    points.push_back(point(p.x(), p.y(), p.z(), kRedBox));
  }
  std::mt19937 random(7);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (int i = 0; i < 60; ++i) points.push_back(point(0.8f * u(random), 0.8f * u(random), 0.7f + 0.4f * u(random), kTable));
  const CloudPtr c = apex_nodes::makeCloud(header(), points);
  pcl::SACSegmentation<pcl::PointXYZ> seg;
  const Fit want = pclFit(seg, *c, pcl::SACMODEL_SPHERE, 0.005, 0.05, 0.2);
  ASSERT_GE(want.inliers.indices.size(), 300u);
  ASSERT_EQ(want.coefficients.values.size(), 4u);
  EXPECT_NEAR(want.coefficients.values[3], 0.08, 1e-3);
  expectFit(c, {{"model", "sphere"}, {"distance_threshold", "0.005"}, {"radius", "[0.05, 0.2]"}}, want);
}

/** A can (r = 4 cm, axis along z) standing on a patch of table, with their normals. */
CloudPtr canWithNormals() {
  pcl::PointCloud<pcl::PointXYZRGBNormal> points;
  auto add = [&](float x, float y, float z, float nx, float ny, float nz, std::uint32_t rgb) {
    pcl::PointXYZRGBNormal p;
    p.x = x, p.y = y, p.z = z, p.normal_x = nx, p.normal_y = ny, p.normal_z = nz, p.curvature = 0;
    p.rgba = 0xff000000u | rgb;
    points.push_back(p);
  };
  for (int a = 0; a < 36; ++a)
    for (int k = 0; k <= 20; ++k) {
      const float t = float(a) * float(M_PI) / 18.f;
      add(0.5f + 0.04f * std::cos(t), 0.4f + 0.04f * std::sin(t), 0.7f + 0.01f * k, std::cos(t), std::sin(t), 0, kRedBox);
    }
  for (int i = 0; i < 15; ++i)
    for (int j = 0; j < 15; ++j) add(0.02f * i, 0.02f * j, 0.7f, 0, 0, 1, kTable);
  return apex_nodes::makeCloud(header(), points);
}

TEST(TableNodes, SACSegmentationFitsACylinderByTheCloudsNormalsAsPclDoes) {
  const CloudPtr can = canWithNormals();
  pcl::SACSegmentationFromNormals<pcl::PointXYZ, pcl::Normal> seg;
  seg.setInputNormals(std::make_shared<pcl::PointCloud<pcl::Normal>>(apex_nodes::typedPoints<pcl::Normal>(*can)));
  seg.setNormalDistanceWeight(0.1);
  const Fit want = pclFit(seg, *can, pcl::SACMODEL_CYLINDER, 0.01, 0.01, 0.1);
  ASSERT_EQ(want.coefficients.values.size(), 7u);
  EXPECT_NEAR(want.coefficients.values[6], 0.04, 1e-3);
  EXPECT_NEAR(std::abs(want.coefficients.values[5]), 1.0, 1e-3);  // the axis: along z
  EXPECT_EQ(want.inliers.indices.size(), 36u * 21u);
  expectFit(can, {{"model", "cylinder"}, {"distance_threshold", "0.01"}, {"radius", "[0.01, 0.1]"}}, want);
}

TEST(TableNodes, NormalPlaneOnNormalEstimationsNormalsIsPcls) {
  NodeHarness normals("apex_nodes/NormalEstimation", {"cloud"}, "cloud");
  normals.set("radius", "0.05");
  const CloudPtr with_normals = cloudOf(normals.run(scene()));
  pcl::SACSegmentationFromNormals<pcl::PointXYZ, pcl::Normal> seg;
  seg.setInputNormals(
      std::make_shared<pcl::PointCloud<pcl::Normal>>(pclNormals(*scene(), [](auto& e) { e.setRadiusSearch(0.05); })));
  seg.setNormalDistanceWeight(0.1);
  const Fit want = pclFit(seg, *scene(), pcl::SACMODEL_NORMAL_PLANE, 0.01);
  EXPECT_GE(want.inliers.indices.size(), kTablePoints * 9 / 10);
  expectFit(with_normals, {{"model", "normal_plane"}, {"distance_threshold", "0.01"}}, want);
}

TEST(TableNodes, AModelThatWeighsNormalsNamesTheMissingFieldAndNormalEstimation) {
  NodeHarness h("apex_nodes/SACSegmentation", {"cloud"}, "inliers");
  h.set("model", "cylinder");
  EXPECT_TRUE(h.run({share(scene())}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("the model 'cylinder' needs each point's normal, and the cloud has no float32 field "
                                   "'normal_x' (its fields: x, y, z, rgb): put a NormalEstimation before the SACSegmentation"));
}

TEST(TableNodes, NoModelFoundNamesTheModelAndThePoints) {
  NodeHarness h("apex_nodes/SACSegmentation", {"cloud"}, "inliers");
  h.set("model", "sphere");
  Rgb three;
  for (int i = 0; i < 3; ++i) three.push_back(point(0.1f * i, 0, 1, kTable));
  EXPECT_TRUE(h.run({share(apex_nodes::makeCloud(header(), three))}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("no sphere found in 3 points (ransac, distance_threshold 0.02)"));
}

TEST(TableNodes, ProjectInliersMovesXyzAsPclDoesAndKeepsTheColours) {
  NodeHarness fit("apex_nodes/SACSegmentation", {"cloud"}, "coefficients");
  fit.set("distance_threshold", "0.01");
  const Message coefficients = fit.run({share(scene())});
  ASSERT_TRUE(coefficients.as<std::vector<double>>());
  NodeHarness h("apex_nodes/ProjectInliers", {"cloud", "coefficients"}, "cloud");
  const CloudPtr got = cloudOf(h.run({share(scene()), coefficients}));
  pcl::ProjectInliers<pcl::PointXYZ> project;
  auto model = std::make_shared<pcl::ModelCoefficients>();
  for (double v : *coefficients.as<std::vector<double>>()) model->values.push_back(float(v));
  project.setModelType(pcl::SACMODEL_PLANE);
  project.setModelCoefficients(model);
  project.setCopyAllData(true);
  project.setInputCloud(std::make_shared<Xyz>(xyz(*scene())));
  Xyz want;
  project.filter(want);
  EXPECT_EQ(apex_nodes::fieldNames(*got->points), "x, y, z, rgb");
  const Rgb points = apex_nodes::typedPoints<pcl::PointXYZRGB>(*got), input = scenePoints();
  ASSERT_EQ(points.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_TRUE(points[i].x == want[i].x && points[i].y == want[i].y && points[i].z == want[i].z) << i;
    ASSERT_NEAR(points[i].z, 0.7, 2e-3) << i;  // onto the table's plane
    ASSERT_EQ(points[i].rgba, input[i].rgba) << i;
  }
  h.set("model", "line");
  EXPECT_TRUE(h.run({share(scene()), coefficients}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("a line has 6 coefficients, the input has 4"));
}

/** The table's points, as SACSegmentation finds them. */
CloudPtr table() {
  NodeHarness fit("apex_nodes/SACSegmentation", {"cloud"}, "inliers");
  fit.set("distance_threshold", "0.01");
  return cloudOf(fit.run({share(scene())}));
}

/** PCL's ConvexHull of the x, y, z of `c`: the hull's indices, and its area and volume. */
std::tuple<pcl::Indices, double, double> pclHull(const Cloud& c, int dimension) {
  pcl::ConvexHull<pcl::PointXYZ> hull;
  hull.setInputCloud(std::make_shared<Xyz>(xyz(c)));
  hull.setDimension(dimension);
  Xyz points;
  hull.reconstruct(points);
  pcl::PointIndices indices;
  hull.getHullPointIndices(indices);
  pcl::ConvexHull<pcl::PointXYZ> measured;  // qhull's "FA": the same hull, measured (and printed)
  measured.setInputCloud(std::make_shared<Xyz>(xyz(c)));
  measured.setDimension(dimension);
  measured.setComputeAreaVolume(true);
  measured.reconstruct(points);
  return {indices.indices, measured.getTotalArea(), measured.getTotalVolume()};
}

TEST(TableNodes, ConvexHullIsPclsHullWithItsPointsWhole) {
  const CloudPtr top = table();
  const auto [indices, area, volume] = pclHull(*top, 2);
  for (const char* dimension : {"auto", "2"})
    for (const char* output : {"hull", "area", "volume"}) {
      NodeHarness h("apex_nodes/ConvexHull", {"cloud"}, output);
      h.set("dimension", dimension);
      const Message got = h.run({share(top)});
      ASSERT_FALSE(got.isNothing()) << h.error() << " (dimension " << dimension << ")";
      if (std::string(output) == "hull") {
        expectSelected(*cloudOf(got), *top, indices);
        EXPECT_EQ(countColour(*cloudOf(got), kTable), indices.size());
      }
      // qhull's 2D area is the polygon's seen along z; the node's, in its plane: here ~level
      if (std::string(output) == "area") {
        EXPECT_NEAR(*got.as<double>(), area, 1e-4 * area);
      }
      if (std::string(output) == "volume") {
        EXPECT_EQ(*got.as<double>(), 0.0);
      }
    }
  EXPECT_NEAR(area, 1.2 * 0.8, 1e-4);
  EXPECT_EQ(volume, 0.0);

  // In 3D: a box.
  const Rgb all = scenePoints();
  pcl::Indices red;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (colour(all[i]) == kRedBox) red.push_back(pcl::index_t(i));
  auto box = std::make_shared<Cloud>();
  box->header = header();
  box->points = apex_nodes::selectPoints(*scene()->points, red);
  const auto [box_indices, box_area, box_volume] = pclHull(*box, 3);
  EXPECT_NEAR(box_volume, 0.1 * 0.1 * 0.14, 1e-5);
  for (const char* output : {"hull", "area", "volume"}) {
    NodeHarness h("apex_nodes/ConvexHull", {"cloud"}, output);
    h.set("dimension", "3");
    const Message got = h.run({share(box)});
    ASSERT_FALSE(got.isNothing()) << h.error();
    if (std::string(output) == "hull") expectSelected(*cloudOf(got), *box, box_indices);
    if (std::string(output) == "area") {
      EXPECT_NEAR(*got.as<double>(), box_area, 1e-6 * box_area);
    }
    if (std::string(output) == "volume") {
      EXPECT_NEAR(*got.as<double>(), box_volume, 1e-6 * box_volume);
    }
  }
}

TEST(TableNodes, ExtractPolygonalPrismGivesTheBoxesOnTheTableAsPclDoes) {
  NodeHarness convex("apex_nodes/ConvexHull", {"cloud"}, "hull");
  const CloudPtr hull = cloudOf(convex.run({share(table())}));
  NodeHarness h("apex_nodes/ExtractPolygonalPrism", {"cloud", "hull"}, "cloud");
  h.set("viewpoint", "[0, 0, 2]");  // above the table: heights count up
  pcl::ExtractPolygonalPrismData<pcl::PointXYZ> prism;
  prism.setInputCloud(std::make_shared<Xyz>(xyz(*scene())));
  prism.setInputPlanarHull(std::make_shared<Xyz>(xyz(*hull)));
  prism.setHeightLimits(0.01, 0.5);
  prism.setViewPoint(0, 0, 2);
  pcl::PointIndices want;
  prism.segment(want);
  const CloudPtr objects = cloudOf(h.run({share(scene()), share(hull)}));
  expectSelected(*objects, *scene(), want.indices);
  EXPECT_EQ(apex_nodes::pointCount(*objects), kBoxPoints);  // the two boxes, nothing else
  EXPECT_EQ(countColour(*objects, kRedBox) + countColour(*objects, kBlueBox), kBoxPoints);

  h.set("negative", "true");
  const CloudPtr rest = cloudOf(h.run({share(scene()), share(hull)}));
  expectSelected(*rest, *scene(), apex_nodes::complement(want.indices, kScenePoints));
  EXPECT_EQ(countColour(*rest, kTable) + countColour(*rest, kBeside) + countColour(*rest, kBelow), kScenePoints - kBoxPoints);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
