// ClusterFeatures against PCL's own computation (centroid, min/max, pcl::PCA's axes) on boxes of
// points whose true size is known, one of them turned; and the markers MarkerPublisher sends for
// them (clusterMarkers, markers.hpp): ids, DELETEALL when clusters went away, labels, header.
#include <gmock/gmock.h>
#include <pcl/common/centroid.h>
#include <pcl/common/common.h>
#include <pcl/common/pca.h>

#include <algorithm>
#include <cmath>

#include "apex/ros/inspect.hpp"
#include "apex_nodes/cloud.hpp"
#include "apex_nodes/cluster_features.hpp"
#include "apex_nodes/markers.hpp"
#include "apex_nodes/stamp.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using apex_nodes::ClusterFeature;
using apex_nodes::ClusterFeatures;
using apex_nodes::Clusters;
using ::testing::HasSubstr;
using visualization_msgs::Marker;
using Xyz = pcl::PointCloud<pcl::PointXYZ>;

namespace {

std_msgs::Header lidarHeader() {
  std_msgs::Header h;
  h.frame_id = "lidar";
  h.stamp = ros::Time(5, 123456789);
  h.seq = 7;
  return h;
}

/** A solid box of points `size` big, on a grid that includes its corners, turned `yaw` about z
 *  and centred at `centre`. The sides differ, so its principal axes are its own. */
Xyz box(const Eigen::Vector3f& size, double yaw, const Eigen::Vector3f& centre) {
  const Eigen::Matrix3f turn = Eigen::AngleAxisf(static_cast<float>(yaw), Eigen::Vector3f::UnitZ()).toRotationMatrix();
  const int n[3] = {17, 9, 5};
  Xyz out;
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) {
        const Eigen::Vector3f local(size.x() * (float(i) / (n[0] - 1) - 0.5f), size.y() * (float(j) / (n[1] - 1) - 0.5f),
                                    size.z() * (float(k) / (n[2] - 1) - 0.5f));
        const Eigen::Vector3f p = centre + turn * local;
        out.push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
      }
  return out;
}

const Eigen::Vector3f kStraightSize(0.6f, 0.3f, 0.1f), kTurnedSize(0.8f, 0.4f, 0.2f);
const Eigen::Vector3f kStraightCentre(1.f, 2.f, 0.5f), kTurnedCentre(-1.f, 0.5f, 0.3f);
const double kYaw = M_PI / 6;  // 30 degrees

/** The straight box with one NaN point (not counted, not measured), the turned one, as a cloud's
 *  clusters. */
std::vector<Xyz> boxes() {
  Xyz straight = box(kStraightSize, 0, kStraightCentre);
  straight.push_back(pcl::PointXYZ(std::nanf(""), 0.f, 0.f));
  straight.is_dense = false;
  return {straight, box(kTurnedSize, kYaw, kTurnedCentre)};
}

std::shared_ptr<const Clusters> clusters(const std::vector<Xyz>& typed) {
  auto out = std::make_shared<Clusters>();
  out->header = lidarHeader();
  for (const auto& c : typed) out->clusters.push_back(apex_nodes::toBlob(c));
  return out;
}

Xyz finitePoints(const Xyz& c) {
  Xyz out;
  for (const auto& p : c)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) out.push_back(p);
  return out;
}

void expectNear(const Eigen::Vector3d& got, const Eigen::Vector3d& want, double tolerance, const std::string& what) {
  EXPECT_LT((got - want).cwiseAbs().maxCoeff(), tolerance)
      << what << ": got " << got.transpose() << ", want " << want.transpose();
}

const ClusterFeatures& features(const Message& m) {
  auto f = m.as<ClusterFeatures>();
  if (!f) throw std::runtime_error("expected cluster features, got " + m.typeName());
  return *f;
}

TEST(ClusterFeatures, MatchesPclsCentroidBoxAndPrincipalAxes) {
  NodeHarness h("apex_nodes/ClusterFeatures", {"clusters"}, "features");
  const auto typed = boxes();
  const ClusterFeatures& got = features(h.run(clusters(typed)));
  EXPECT_EQ(got.header, lidarHeader());
  ASSERT_EQ(got.clusters.size(), typed.size());
  for (std::size_t i = 0; i < typed.size(); ++i) {
    SCOPED_TRACE("cluster " + std::to_string(i));
    const ClusterFeature& f = got.clusters[i];
    const Xyz finite = finitePoints(typed[i]);
    EXPECT_EQ(f.label, int(i));
    EXPECT_EQ(f.points, finite.size());

    Eigen::Vector4f centroid;
    pcl::compute3DCentroid(typed[i], centroid);  // skips the NaN: the cloud is not dense
    expectNear(f.centroid, centroid.head<3>().cast<double>(), 1e-5, "centroid");
    pcl::PointXYZ low, high;
    pcl::getMinMax3D(typed[i], low, high);
    expectNear(f.min, low.getVector3fMap().cast<double>(), 1e-6, "min");
    expectNear(f.max, high.getVector3fMap().cast<double>(), 1e-6, "max");
    expectNear(f.extent, (high.getVector3fMap() - low.getVector3fMap()).cast<double>(), 1e-6, "extent");

    // pcl::PCA: the same axes (up to their sign), largest spread first; its coefficients are the
    // points along them, whose ranges are the oriented box.
    pcl::PCA<pcl::PointXYZ> pca;
    pca.setInputCloud(std::make_shared<Xyz>(finite));
    const Eigen::Matrix3d axes = f.oriented.orientation.toRotationMatrix();
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(std::abs(axes.col(k).dot(pca.getEigenVectors().col(k).cast<double>())), 1.0, 1e-5) << "axis " << k;
    const Eigen::MatrixXf& along = pca.getCoefficients();
    const Eigen::Vector3f from = along.rowwise().minCoeff(), to = along.rowwise().maxCoeff();
    expectNear(f.oriented.extent, (to - from).cast<double>(), 1e-4, "oriented extent");
    const Eigen::Vector3f centre = pca.getMean().head<3>() + pca.getEigenVectors() * (0.5f * (from + to));
    expectNear(f.oriented.centre, centre.cast<double>(), 1e-4, "oriented centre");
  }
}

TEST(ClusterFeatures, OrientedBoxIsTheTurnedBoxsTrueSize) {
  NodeHarness h("apex_nodes/ClusterFeatures", {"clusters"}, "features");
  const ClusterFeatures& got = features(h.run(clusters(boxes())));
  ASSERT_EQ(got.clusters.size(), 2u);
  const ClusterFeature& straight = got.clusters[0];
  expectNear(straight.extent, kStraightSize.cast<double>(), 1e-5, "straight: axis-aligned extent");
  expectNear(straight.oriented.extent, kStraightSize.cast<double>(), 1e-5, "straight: oriented extent");
  expectNear(straight.centre(), kStraightCentre.cast<double>(), 1e-5, "straight: centre");

  const ClusterFeature& turned = got.clusters[1];
  expectNear(turned.oriented.extent, kTurnedSize.cast<double>(), 1e-5, "turned: oriented extent");
  expectNear(turned.oriented.centre, kTurnedCentre.cast<double>(), 1e-5, "turned: oriented centre");
  expectNear(turned.centroid, kTurnedCentre.cast<double>(), 1e-5, "turned: centroid");
  const double c = std::cos(kYaw), s = std::sin(kYaw);  // the axis-aligned box holds the turned corners
  expectNear(turned.extent, Eigen::Vector3d(0.8 * c + 0.4 * s, 0.8 * s + 0.4 * c, 0.2), 1e-5, "turned: axis-aligned extent");
  // Its longest axis is the box's x turned by 30 degrees, its shortest z; a proper rotation.
  const Eigen::Matrix3d axes = turned.oriented.orientation.toRotationMatrix();
  EXPECT_NEAR(turned.oriented.orientation.norm(), 1.0, 1e-9);
  EXPECT_NEAR(axes.determinant(), 1.0, 1e-9);
  EXPECT_NEAR(std::abs(axes.col(0).dot(Eigen::Vector3d(c, s, 0))), 1.0, 1e-6);
  EXPECT_NEAR(std::abs(axes.col(2).z()), 1.0, 1e-6);
}

// A box 5 km from the cloud's origin (a map frame, GPS): its float points lie on a grid of half a
// millimetre there; the features, in double from sums shifted to the first point, stay within a
// millimetre of the true size and centre.
TEST(ClusterFeatures, FarFromTheOriginKeepsMillimetres) {
  const Eigen::Vector3f far(5000.f, -3000.f, 100.f);
  NodeHarness h("apex_nodes/ClusterFeatures", {"clusters"}, "features");
  const ClusterFeatures& got = features(h.run(clusters({box(kTurnedSize, kYaw, far)})));
  ASSERT_EQ(got.clusters.size(), 1u);
  const ClusterFeature& f = got.clusters[0];
  expectNear(f.oriented.extent, kTurnedSize.cast<double>(), 1e-3, "oriented extent");
  expectNear(f.oriented.centre, far.cast<double>(), 1e-3, "oriented centre");
  expectNear(f.centroid, far.cast<double>(), 1e-3, "centroid");
}

TEST(ClusterFeatures, EachOrientedBoxIsAlsoAPoseForRviz) {
  NodeHarness h("apex_nodes/ClusterFeatures", {"clusters"}, "poses");
  const auto poses = h.run(clusters(boxes())).as<geometry_msgs::PoseArray>();
  ASSERT_TRUE(poses);
  EXPECT_EQ(poses->header, lidarHeader());
  ASSERT_EQ(poses->poses.size(), 2u);
  const auto& turned = poses->poses[1];
  expectNear(Eigen::Vector3d(turned.position.x, turned.position.y, turned.position.z), kTurnedCentre.cast<double>(), 1e-5,
             "turned: pose position");
  const Eigen::Quaterniond q(turned.orientation.w, turned.orientation.x, turned.orientation.y, turned.orientation.z);
  EXPECT_NEAR(std::abs(q.toRotationMatrix().col(0).dot(Eigen::Vector3d(std::cos(kYaw), std::sin(kYaw), 0))), 1.0, 1e-6);
}

TEST(Markers, AHullIsAClosedOutlineInItsFrame) {
  Xyz square;
  for (auto [x, y] : {std::pair{0.f, 0.f}, {1.f, 0.f}, {1.f, 1.f}, {0.f, 1.f}}) square.push_back(pcl::PointXYZ(x, y, 0.7f));
  const auto hull = apex_nodes::makeCloud(lidarHeader(), square);
  const auto m = apex_nodes::hullMarker(*hull, apex_nodes::MarkerOptions());
  EXPECT_EQ(m.header, lidarHeader());
  EXPECT_EQ(m.type, visualization_msgs::Marker::LINE_STRIP);
  EXPECT_EQ(m.ns, "clusters/plane");
  ASSERT_EQ(m.points.size(), 5u);  // closed: back to the first corner
  EXPECT_EQ(m.points.back(), m.points.front());
  EXPECT_EQ(m.points[2].x, 1.0);
  Xyz two;
  two.push_back(square[0]), two.push_back(square[1]);
  EXPECT_THROW(apex_nodes::hullMarker(*apex_nodes::makeCloud(lidarHeader(), two), apex_nodes::MarkerOptions()),
               std::invalid_argument);
}

TEST(Markers, ImageRegionsAreRaysAndBoxesFromTheCamera) {
  sensor_msgs::CameraInfo camera;
  camera.P = {100, 0, 50, 0, 0, 100, 40, 0, 0, 0, 1, 0};
  apex_nodes::Regions regions;
  regions.header.frame_id = "camera";
  apex_nodes::Region r;
  r.centroid = cv::Point2d(150, 40), r.box = cv::Rect(50, 40, 100, 20);
  regions.regions = {r};
  apex_nodes::MarkerOptions options;
  options.ray_length = 2.0;
  const auto m = apex_nodes::regionRays(regions, camera, options);
  EXPECT_EQ(m.header.frame_id, "camera");
  EXPECT_EQ(m.type, visualization_msgs::Marker::LINE_LIST);
  ASSERT_EQ(m.points.size(), 2u + 8u);  // the ray, the box's four edges
  EXPECT_EQ(m.points[0], geometry_msgs::Point());  // from the camera's origin
  EXPECT_DOUBLE_EQ(m.points[1].x, 2.0);  // u 150: one focal length right of the centre at depth 2
  EXPECT_DOUBLE_EQ(m.points[1].y, 0.0);
  EXPECT_DOUBLE_EQ(m.points[1].z, 2.0);
  EXPECT_DOUBLE_EQ(m.points[2].x, 0.0);  // the box's corner (50, 40): on the axis
  camera.P = {};
  EXPECT_THROW(apex_nodes::regionRays(regions, camera, options), std::invalid_argument);
}

TEST(ClusterFeatures, CountsClustersAndMeasuresEmptyOnesAsNothing) {
  NodeHarness h("apex_nodes/ClusterFeatures", {"clusters"}, "count");
  auto typed = boxes();
  Xyz nans;
  nans.push_back(pcl::PointXYZ(std::nanf(""), std::nanf(""), std::nanf("")));
  nans.is_dense = false;
  typed.push_back(nans);
  typed.push_back(Xyz());
  auto count = h.run(clusters(typed)).as<int>();
  ASSERT_TRUE(count);
  EXPECT_EQ(*count, 4);

  NodeHarness f("apex_nodes/ClusterFeatures", {"clusters"}, "features");
  const ClusterFeatures& got = features(f.run(clusters(typed)));
  ASSERT_EQ(got.clusters.size(), 4u);
  for (std::size_t i : {2u, 3u}) {
    EXPECT_EQ(got.clusters[i].label, int(i));
    EXPECT_EQ(got.clusters[i].points, 0u);
    EXPECT_TRUE(got.clusters[i].extent.isZero() && got.clusters[i].oriented.extent.isZero());
  }
  EXPECT_TRUE(features(f.run(clusters({}))).clusters.empty());
}

TEST(ClusterFeatures, AClusterWithoutZNamesIt) {
  NodeHarness h("apex_nodes/ClusterFeatures", {"clusters"}, "features");
  auto c = std::make_shared<Clusters>(*clusters(boxes()));
  pcl::PointCloud<pcl::PointXY> flat;
  flat.push_back(pcl::PointXY(1.f, 2.f));
  c->clusters.push_back(apex_nodes::toBlob(flat));
  EXPECT_TRUE(h.run(std::shared_ptr<const Clusters>(c)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("cluster 2: point cloud 1x1 on frame 'lidar' has no field 'z' (its fields: x, y)"));
}

// ---- the markers ----

/** `n` clusters: cluster i is a box i + 1 points strong at x = i, flat in z. */
ClusterFeatures someFeatures(std::size_t n) {
  ClusterFeatures out;
  out.header = lidarHeader();
  for (std::size_t i = 0; i < n; ++i) {
    ClusterFeature f;
    f.label = int(i);
    f.points = i + 1;
    f.min = Eigen::Vector3d(double(i), 0, 1), f.max = Eigen::Vector3d(double(i) + 0.5, 0.2, 1);  // flat: z extent 0
    f.extent = f.max - f.min;
    f.centroid = f.centre();
    f.oriented.centre = f.centre() + Eigen::Vector3d(0.01, 0, 0);
    f.oriented.extent = Eigen::Vector3d(0.6, 0.1, 0.05);
    f.oriented.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));
    out.clusters.push_back(f);
  }
  return out;
}

std::vector<const Marker*> inNamespace(const visualization_msgs::MarkerArray& a, const std::string& ns) {
  std::vector<const Marker*> out;
  for (const auto& m : a.markers)
    if (m.ns == ns && m.action != Marker::DELETEALL) out.push_back(&m);
  return out;
}

int deleteAlls(const visualization_msgs::MarkerArray& a) {
  return int(std::count_if(a.markers.begin(), a.markers.end(), [](const Marker& m) { return m.action == Marker::DELETEALL; }));
}

TEST(ClusterMarkers, OneBoxPerClusterIdsByIndexWithTheHeader) {
  apex_nodes::MarkerOptions o;
  o.labels = false;
  o.color = {255, 0, 51};
  o.alpha = 0.25;
  const auto a = apex_nodes::clusterMarkers(someFeatures(3), o, 3);
  ASSERT_EQ(a.markers.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const Marker& m = a.markers[i];
    EXPECT_EQ(m.header, lidarHeader());
    EXPECT_EQ(m.ns, "clusters");
    EXPECT_EQ(m.id, int(i));
    EXPECT_EQ(m.type, Marker::CUBE);
    EXPECT_EQ(m.action, Marker::ADD);
    EXPECT_DOUBLE_EQ(m.pose.position.x, i + 0.25);
    EXPECT_DOUBLE_EQ(m.pose.position.y, 0.1);
    EXPECT_DOUBLE_EQ(m.pose.orientation.w, 1.0);
    EXPECT_DOUBLE_EQ(m.scale.x, 0.5);
    EXPECT_NEAR(m.scale.y, 0.2, 1e-12);
    EXPECT_DOUBLE_EQ(m.scale.z, 0.001);  // flat, yet shown
    EXPECT_FLOAT_EQ(m.color.r, 1.f);
    EXPECT_FLOAT_EQ(m.color.g, 0.f);
    EXPECT_FLOAT_EQ(m.color.b, 0.2f);
    EXPECT_FLOAT_EQ(m.color.a, 0.25f);
    EXPECT_EQ(m.lifetime, ros::Duration(0));
  }
}

TEST(ClusterMarkers, DeleteAllFirstOnlyWhenClustersWentAway) {
  apex_nodes::MarkerOptions o;
  o.ns = "objects";
  const auto shrunk = apex_nodes::clusterMarkers(someFeatures(2), o, 5);
  ASSERT_FALSE(shrunk.markers.empty());
  EXPECT_EQ(shrunk.markers[0].action, Marker::DELETEALL);
  EXPECT_EQ(shrunk.markers[0].id, 0);
  EXPECT_EQ(shrunk.markers[0].ns, "objects");
  EXPECT_EQ(shrunk.markers[0].header, lidarHeader());  // rviz drops a marker whose frame it cannot place
  EXPECT_EQ(deleteAlls(shrunk), 1);
  EXPECT_EQ(inNamespace(shrunk, "objects").size(), 2u);

  EXPECT_EQ(deleteAlls(apex_nodes::clusterMarkers(someFeatures(2), o, 2)), 0);  // stays
  EXPECT_EQ(deleteAlls(apex_nodes::clusterMarkers(someFeatures(3), o, 2)), 0);  // grows
  EXPECT_EQ(deleteAlls(apex_nodes::clusterMarkers(someFeatures(1), o, 0)), 0);
  const auto none = apex_nodes::clusterMarkers(someFeatures(0), o, 1);  // all gone: only the DELETEALL
  ASSERT_EQ(none.markers.size(), 1u);
  EXPECT_EQ(none.markers[0].action, Marker::DELETEALL);
  EXPECT_TRUE(apex_nodes::clusterMarkers(someFeatures(0), o, 0).markers.empty());
  EXPECT_EQ(deleteAlls(apex_nodes::clusterMarkers(someFeatures(4), o, apex_nodes::kUnknownMarkerCount)), 1);
}

TEST(ClusterMarkers, LabelsAboveEachBoxWithLabelAndPointCount) {
  apex_nodes::MarkerOptions o;  // labels on by default
  const auto a = apex_nodes::clusterMarkers(someFeatures(3), o, 0);
  const auto cubes = inNamespace(a, "clusters");
  const auto texts = inNamespace(a, "clusters/labels");
  ASSERT_EQ(cubes.size(), 3u);
  ASSERT_EQ(texts.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const Marker& t = *texts[i];
    EXPECT_EQ(t.id, int(i));
    EXPECT_EQ(t.type, Marker::TEXT_VIEW_FACING);
    EXPECT_EQ(t.header, lidarHeader());
    EXPECT_EQ(t.text, std::to_string(i) + ": " + std::to_string(i + 1) + " points");
    EXPECT_DOUBLE_EQ(t.pose.position.x, cubes[i]->pose.position.x);
    EXPECT_GT(t.pose.position.z, cubes[i]->pose.position.z);
    EXPECT_GT(t.scale.z, 0.0);
    EXPECT_FLOAT_EQ(t.color.a, 1.f);
  }
  o.labels = false;
  EXPECT_TRUE(inNamespace(apex_nodes::clusterMarkers(someFeatures(3), o, 0), "clusters/labels").empty());
}

TEST(ClusterMarkers, OrientedBoxesTurnAndLastTheirLifetime) {
  apex_nodes::MarkerOptions o;
  o.oriented = true;
  o.labels = false;
  o.lifetime = 2.5;
  const ClusterFeatures f = someFeatures(1);
  const auto a = apex_nodes::clusterMarkers(f, o, 0);
  ASSERT_EQ(a.markers.size(), 1u);
  const Marker& m = a.markers[0];
  EXPECT_DOUBLE_EQ(m.pose.position.x, f.clusters[0].oriented.centre.x());
  EXPECT_DOUBLE_EQ(m.pose.orientation.z, f.clusters[0].oriented.orientation.z());
  EXPECT_DOUBLE_EQ(m.pose.orientation.w, f.clusters[0].oriented.orientation.w());
  EXPECT_DOUBLE_EQ(m.scale.x, 0.6);
  EXPECT_DOUBLE_EQ(m.scale.z, 0.05);
  EXPECT_EQ(m.lifetime, ros::Duration(2.5));
}

TEST(ClusterMarkers, AClusterWithoutPointsDeletesItsMarkers) {
  ClusterFeatures f = someFeatures(2);
  f.clusters[1] = ClusterFeature();
  f.clusters[1].label = 1;
  const auto a = apex_nodes::clusterMarkers(f, apex_nodes::MarkerOptions(), 2);
  ASSERT_EQ(a.markers.size(), 4u);  // box and label of 0, DELETE of box and label 1
  EXPECT_EQ(a.markers[2].action, Marker::DELETE);
  EXPECT_EQ(a.markers[2].id, 1);
  EXPECT_EQ(a.markers[2].ns, "clusters");
  EXPECT_EQ(a.markers[3].action, Marker::DELETE);
  EXPECT_EQ(a.markers[3].ns, "clusters/labels");
}

TEST(ClusterMarkers, ClusterFeaturesAreInspectedAndRecordedAsMarkers) {
  const apex::Inspector inspector = apex::findInspector(apex::typeOf<ClusterFeatures>());
  EXPECT_EQ(inspector.message_type, "visualization_msgs/MarkerArray");
  const apex::Message m = apex::Message::make(someFeatures(2));
  ASSERT_TRUE(inspector.serialize);
  const apex::SerializedMessage recorded = inspector.serialize(m);
  EXPECT_EQ(recorded.datatype, "visualization_msgs/MarkerArray");
  EXPECT_FALSE(recorded.bytes.empty());
  EXPECT_EQ(recorded.stamp, lidarHeader().stamp);  // a MarkerArray has no header: the features' stamp
  ASSERT_TRUE(inspector.describe);
  EXPECT_EQ(inspector.describe(m), "2 clusters");
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
