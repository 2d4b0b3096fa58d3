// The image library's results as ROS messages (ros_results.hpp): each toRos gives the result field
// by field; Regions come back through fromRos; ~inspect's registry has each as its apex/ message,
// stamped with the result's header (so BagWriter records it at that stamp: Regions recorded and
// read back); ResultPublisher names a type with no ROS form and lists those with one; keypoints as
// MarkerPublisher draws them (its tracks: test_markers). No master: nothing here advertises.
#include <gmock/gmock.h>
#include <rosbag/view.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "apex/ros/inspect.hpp"
#include "apex_nodes/markers.hpp"
#include "apex_nodes/ros_results.hpp"
#include "apex_test/node_harness.hpp"
#include "apex_test/test_bags.hpp"

/** A type with no ROS form (no inspector registered). */
struct NoRosForm {};
APEX_TYPE_NAME(NoRosForm, "test/NoRosForm");

using namespace apex_test;
using testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

std_msgs::Header header() {
  std_msgs::Header h;
  h.stamp = ros::Time(1700000000, 123456789);
  h.frame_id = "camera";
  h.seq = 7;
  return h;
}

template <class Msg>
void expectHeaderAndSize(const Msg& m, std::uint32_t width = 640, std::uint32_t height = 480) {
  EXPECT_EQ(m.header.stamp, header().stamp);
  EXPECT_EQ(m.header.frame_id, "camera");
  EXPECT_EQ(m.header.seq, 7u);
  EXPECT_EQ(m.width, width);
  EXPECT_EQ(m.height, height);
}

apex_nodes::Regions regions() {
  apex_nodes::Regions r;
  r.header = header();
  r.image_size = cv::Size(640, 480);
  apex_nodes::Region a;
  a.box = cv::Rect(10, 20, 30, 40), a.area = 1000.5, a.centroid = cv::Point2d(25.25, 40.75), a.label = 3, a.confidence = 0.875;
  apex_nodes::Region b;
  b.box = cv::Rect(0, 1, 2, 3), b.area = 4, b.centroid = cv::Point2d(1, 2.5);  // no label: -1, confidence 0
  r.regions = {a, b};
  return r;
}

apex_nodes::Keypoints keypoints(int depth) {
  apex_nodes::Keypoints k;
  k.header = header();
  k.image_size = cv::Size(640, 480);
  k.keypoints = {cv::KeyPoint(1.5f, 2.5f, 7.f, 45.f, 0.25f, 1, 2), cv::KeyPoint(100.f, 200.f, 31.f, -1.f, 0.5f, 3, -1)};
  k.method = depth == CV_8U ? "orb" : "sift";
  k.norm_type = depth == CV_8U ? cv::NORM_HAMMING : cv::NORM_L2;
  k.descriptors = cv::Mat(2, 3, depth);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) {
      if (depth == CV_8U) k.descriptors.at<uchar>(r, c) = static_cast<uchar>(10 * r + c);
      else k.descriptors.at<float>(r, c) = 0.5f * (10 * r + c);
    }
  return k;
}

TEST(RosResults, RegionsFieldByFieldAndBackThroughFromRos) {
  const apex_nodes::Regions in = regions();
  const apex::Regions m = apex_nodes::toRos(in);
  expectHeaderAndSize(m);
  ASSERT_EQ(m.regions.size(), 2u);
  EXPECT_EQ(m.regions[0].x, 10);
  EXPECT_EQ(m.regions[0].y, 20);
  EXPECT_EQ(m.regions[0].width, 30);
  EXPECT_EQ(m.regions[0].height, 40);
  EXPECT_EQ(m.regions[0].area, 1000.5);
  EXPECT_EQ(m.regions[0].centroid_x, 25.25);
  EXPECT_EQ(m.regions[0].centroid_y, 40.75);
  EXPECT_EQ(m.regions[0].label, 3);
  EXPECT_EQ(m.regions[0].confidence, 0.875);
  EXPECT_EQ(m.regions[1].label, -1);
  EXPECT_EQ(m.regions[1].confidence, 0.0);

  const apex_nodes::Regions back = apex_nodes::fromRos(m);
  EXPECT_EQ(back.header.stamp, in.header.stamp);
  EXPECT_EQ(back.header.frame_id, in.header.frame_id);
  EXPECT_EQ(back.image_size, in.image_size);
  ASSERT_EQ(back.regions.size(), in.regions.size());
  for (std::size_t i = 0; i < in.regions.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(back.regions[i].box, in.regions[i].box);
    EXPECT_EQ(back.regions[i].area, in.regions[i].area);
    EXPECT_EQ(back.regions[i].centroid, in.regions[i].centroid);
    EXPECT_EQ(back.regions[i].label, in.regions[i].label);
    EXPECT_EQ(back.regions[i].confidence, in.regions[i].confidence);
  }
}

TEST(RosResults, ContoursAsTheirPointsAndTheHierarchyFourPerContour) {
  apex_nodes::Contours in;
  in.header = header();
  in.image_size = cv::Size(640, 480);
  in.contours = {{{1, 2}, {3, 4}, {5, 6}}, {{7, 8}}};
  in.hierarchy = {cv::Vec4i(1, -1, -1, -1), cv::Vec4i(-1, 0, -1, 0)};
  const apex::Contours m = apex_nodes::toRos(in);
  expectHeaderAndSize(m);
  ASSERT_EQ(m.contours.size(), 2u);
  EXPECT_THAT(m.contours[0].x, testing::ElementsAre(1, 3, 5));
  EXPECT_THAT(m.contours[0].y, testing::ElementsAre(2, 4, 6));
  EXPECT_THAT(m.contours[1].x, testing::ElementsAre(7));
  EXPECT_THAT(m.contours[1].y, testing::ElementsAre(8));
  EXPECT_THAT(m.hierarchy, testing::ElementsAre(1, -1, -1, -1, -1, 0, -1, 0));
  in.hierarchy.clear();  // unknown: none
  EXPECT_TRUE(apex_nodes::toRos(in).hierarchy.empty());
}

TEST(RosResults, LinesAndCircles) {
  apex_nodes::Lines lines;
  lines.header = header();
  lines.image_size = cv::Size(640, 480);
  lines.lines = {cv::Vec4f(1.5f, 2.5f, 3.5f, 4.5f)};
  const apex::LineSegments l = apex_nodes::toRos(lines);
  expectHeaderAndSize(l);
  ASSERT_EQ(l.lines.size(), 1u);
  EXPECT_EQ(l.lines[0].x1, 1.5f);
  EXPECT_EQ(l.lines[0].y1, 2.5f);
  EXPECT_EQ(l.lines[0].x2, 3.5f);
  EXPECT_EQ(l.lines[0].y2, 4.5f);

  apex_nodes::Circles circles;
  circles.header = header();
  circles.image_size = cv::Size(640, 480);
  circles.circles = {cv::Vec3f(10.f, 20.f, 5.5f), cv::Vec3f(1.f, 2.f, 3.f)};
  const apex::Circles c = apex_nodes::toRos(circles);
  expectHeaderAndSize(c);
  ASSERT_EQ(c.circles.size(), 2u);
  EXPECT_EQ(c.circles[0].x, 10.f);
  EXPECT_EQ(c.circles[0].y, 20.f);
  EXPECT_EQ(c.circles[0].radius, 5.5f);
  EXPECT_EQ(c.circles[1].radius, 3.f);
}

TEST(RosResults, MarkersWithTheirCornersAndPosesAsQuaternions) {
  apex_nodes::Markers in;
  in.header = header();
  in.image_size = cv::Size(640, 480);
  in.dictionary = "4x4_50";
  in.marker_length = 0.05;
  in.ids = {7, 23};
  in.corners = {{{1, 2}, {3, 2}, {3, 4}, {1, 4}}, {{10, 20}, {30, 20}, {30, 40}, {10, 40}}};
  const apex::FiducialMarkers none = apex_nodes::toRos(in);
  expectHeaderAndSize(none);
  EXPECT_EQ(none.dictionary, "4x4_50");
  EXPECT_EQ(none.marker_length, 0.05);
  ASSERT_EQ(none.markers.size(), 2u);
  EXPECT_EQ(none.markers[0].id, 7);
  EXPECT_EQ(none.markers[1].id, 23);
  ASSERT_EQ(none.markers[1].corners.size(), 4u);
  EXPECT_EQ(none.markers[1].corners[2].x, 30.f);
  EXPECT_EQ(none.markers[1].corners[2].y, 40.f);
  EXPECT_EQ(none.markers[1].corners[2].z, 0.f);
  EXPECT_TRUE(none.poses.empty());  // no camera model

  in.rvecs = {cv::Vec3d(0, 0, M_PI / 2), cv::Vec3d(0, 0, 0)};  // a quarter turn about z; none
  in.tvecs = {cv::Vec3d(0.1, 0.2, 1.5), cv::Vec3d(-1, 0, 2)};
  const apex::FiducialMarkers m = apex_nodes::toRos(in);
  ASSERT_EQ(m.poses.size(), 2u);
  EXPECT_EQ(m.poses[0].position.x, 0.1);
  EXPECT_EQ(m.poses[0].position.y, 0.2);
  EXPECT_EQ(m.poses[0].position.z, 1.5);
  EXPECT_NEAR(m.poses[0].orientation.x, 0.0, 1e-12);
  EXPECT_NEAR(m.poses[0].orientation.y, 0.0, 1e-12);
  EXPECT_NEAR(m.poses[0].orientation.z, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(m.poses[0].orientation.w, std::sqrt(0.5), 1e-12);
  EXPECT_EQ(m.poses[1].orientation.w, 1.0);
  EXPECT_EQ(m.poses[1].position.x, -1.0);
}

TEST(RosResults, ChessboardCorners) {
  apex_nodes::Corners in;
  in.header = header();
  in.image_size = cv::Size(640, 480);
  in.pattern_size = cv::Size(9, 6);
  in.found = true;
  in.corners = {{1.25f, 2.5f}, {3.75f, 4.f}};
  const apex::ChessboardCorners m = apex_nodes::toRos(in);
  expectHeaderAndSize(m);
  EXPECT_EQ(m.pattern_width, 9u);
  EXPECT_EQ(m.pattern_height, 6u);
  EXPECT_TRUE(m.found);
  ASSERT_EQ(m.corners.size(), 2u);
  EXPECT_EQ(m.corners[0].x, 1.25f);
  EXPECT_EQ(m.corners[0].y, 2.5f);
  EXPECT_EQ(m.corners[1].x, 3.75f);
  EXPECT_EQ(m.corners[1].y, 4.f);
}

TEST(RosResults, KeypointsWithBinaryOrFloatDescriptors) {
  const apex::Keypoints b = apex_nodes::toRos(keypoints(CV_8U));
  expectHeaderAndSize(b);
  EXPECT_EQ(b.method, "orb");
  EXPECT_EQ(b.norm_type, cv::NORM_HAMMING);
  ASSERT_EQ(b.keypoints.size(), 2u);
  EXPECT_EQ(b.keypoints[0].x, 1.5f);
  EXPECT_EQ(b.keypoints[0].y, 2.5f);
  EXPECT_EQ(b.keypoints[0].size, 7.f);
  EXPECT_EQ(b.keypoints[0].angle, 45.f);
  EXPECT_EQ(b.keypoints[0].response, 0.25f);
  EXPECT_EQ(b.keypoints[0].octave, 1);
  EXPECT_EQ(b.keypoints[0].class_id, 2);
  EXPECT_EQ(b.keypoints[1].angle, -1.f);
  EXPECT_EQ(b.keypoints[1].class_id, -1);
  EXPECT_EQ(b.descriptor_rows, 2u);
  EXPECT_EQ(b.descriptor_cols, 3u);
  EXPECT_THAT(b.descriptors_binary, testing::ElementsAre(0, 1, 2, 10, 11, 12));
  EXPECT_TRUE(b.descriptors_float.empty());

  const apex::Keypoints f = apex_nodes::toRos(keypoints(CV_32F));
  EXPECT_EQ(f.method, "sift");
  EXPECT_EQ(f.norm_type, cv::NORM_L2);
  EXPECT_EQ(f.descriptor_rows, 2u);
  EXPECT_EQ(f.descriptor_cols, 3u);
  EXPECT_THAT(f.descriptors_float, testing::ElementsAre(0.f, 0.5f, 1.f, 5.f, 5.5f, 6.f));
  EXPECT_TRUE(f.descriptors_binary.empty());

  apex_nodes::Keypoints none = keypoints(CV_8U);
  none.descriptors = cv::Mat();  // fast, gftt
  const apex::Keypoints n = apex_nodes::toRos(none);
  EXPECT_EQ(n.descriptor_rows, 0u);
  EXPECT_TRUE(n.descriptors_binary.empty() && n.descriptors_float.empty());
}

TEST(RosResults, MatchesWithBothSetsOfKeypoints) {
  apex_nodes::Matches in;
  in.header = header();
  in.matches = {cv::DMatch(0, 1, 2.5f), cv::DMatch(1, 0, 3, 7.25f)};
  in.query = std::make_shared<apex_nodes::Keypoints>(keypoints(CV_8U));
  const apex::Matches m = apex_nodes::toRos(in);
  EXPECT_EQ(m.header.stamp, header().stamp);
  ASSERT_EQ(m.matches.size(), 2u);
  EXPECT_EQ(m.matches[0].query_idx, 0);
  EXPECT_EQ(m.matches[0].train_idx, 1);
  EXPECT_EQ(m.matches[0].img_idx, -1);
  EXPECT_EQ(m.matches[0].distance, 2.5f);
  EXPECT_EQ(m.matches[1].query_idx, 1);
  EXPECT_EQ(m.matches[1].train_idx, 0);
  EXPECT_EQ(m.matches[1].img_idx, 3);
  EXPECT_EQ(m.matches[1].distance, 7.25f);
  EXPECT_EQ(m.query, apex_nodes::toRos(*in.query));
  EXPECT_TRUE(m.train.keypoints.empty());  // none known

  in.train = std::make_shared<apex_nodes::Keypoints>(keypoints(CV_32F));
  EXPECT_EQ(apex_nodes::toRos(in).train, apex_nodes::toRos(*in.train));
}

TEST(RosResults, HomographyRowByRowOrZerosWhenNoneWasFound) {
  apex_nodes::Homography in;
  in.header = header();
  in.image_size = cv::Size(640, 480);
  in.matrix = (cv::Mat_<double>(3, 3) << 1, 2, 3, 4, 5, 6, 7, 8, 9);
  in.inlier_mask = {1, 0, 1};
  in.inliers = 2;
  const apex::Homography m = apex_nodes::toRos(in);
  expectHeaderAndSize(m);
  EXPECT_TRUE(m.found);
  EXPECT_THAT(m.matrix, testing::ElementsAre(1, 2, 3, 4, 5, 6, 7, 8, 9));
  EXPECT_EQ(m.inliers, 2);
  EXPECT_THAT(m.inlier_mask, testing::ElementsAre(1, 0, 1));

  in.matrix = cv::Mat();  // too few inliers: none, but what it had stays
  const apex::Homography none = apex_nodes::toRos(in);
  EXPECT_FALSE(none.found);
  EXPECT_THAT(none.matrix, testing::Each(0.0));
  EXPECT_EQ(none.inliers, 2);
  EXPECT_THAT(none.inlier_mask, testing::ElementsAre(1, 0, 1));
}

TEST(RosResults, Tracks) {
  apex_nodes::Tracks in;
  in.header = header();
  in.image_size = cv::Size(640, 480);
  in.previous = {{1.f, 2.f}, {3.f, 4.f}};
  in.current = {{1.5f, 2.5f}, {0.f, 0.f}};
  in.status = {1, 0};
  const apex::Tracks m = apex_nodes::toRos(in);
  expectHeaderAndSize(m);
  ASSERT_EQ(m.previous.size(), 2u);
  ASSERT_EQ(m.current.size(), 2u);
  EXPECT_EQ(m.previous[1].x, 3.f);
  EXPECT_EQ(m.previous[1].y, 4.f);
  EXPECT_EQ(m.current[0].x, 1.5f);
  EXPECT_EQ(m.current[0].y, 2.5f);
  EXPECT_THAT(m.status, testing::ElementsAre(1, 0));
}

/** T's registered form: its ROS type, and a serialized message stamped with the header's stamp. */
template <class T>
void expectForm(const T& value, const std::string& ros_type) {
  SCOPED_TRACE(ros_type);
  pluginRegistry();  // apex_nodes_ros loaded: its inspectors registered
  const apex::Inspector inspector = apex::findInspector(apex::typeOf<T>());
  EXPECT_EQ(inspector.message_type, ros_type);
  ASSERT_TRUE(inspector.serialize);
  const apex::SerializedMessage s = inspector.serialize(apex::Message::make<T>(value));
  EXPECT_EQ(s.datatype, ros_type);
  EXPECT_EQ(s.stamp, header().stamp);  // BagWriter's record time
  EXPECT_FALSE(s.bytes.empty());
  ASSERT_TRUE(inspector.describe);
  EXPECT_FALSE(inspector.describe(apex::Message::make<T>(value)).empty());
}

TEST(RosResults, EachTypeHasItsFormInTheInspectRegistry) {
  expectForm(regions(), "apex/Regions");
  apex_nodes::Contours contours;
  contours.header = header();
  expectForm(contours, "apex/Contours");
  apex_nodes::Lines lines;
  lines.header = header();
  expectForm(lines, "apex/LineSegments");
  apex_nodes::Circles circles;
  circles.header = header();
  expectForm(circles, "apex/Circles");
  apex_nodes::Markers markers;
  markers.header = header();
  expectForm(markers, "apex/FiducialMarkers");
  apex_nodes::Corners corners;
  corners.header = header();
  expectForm(corners, "apex/ChessboardCorners");
  expectForm(keypoints(CV_8U), "apex/Keypoints");
  apex_nodes::Matches matches;
  matches.header = header();
  expectForm(matches, "apex/Matches");
  apex_nodes::Homography homography;
  homography.header = header();
  expectForm(homography, "apex/Homography");
  apex_nodes::Tracks tracks;
  tracks.header = header();
  expectForm(tracks, "apex/Tracks");

  // The bytes are the message itself: read back, they are what toRos gives.
  const apex::SerializedMessage s =
      apex::findInspector(apex::typeOf<apex_nodes::Regions>()).serialize(apex::Message::make<apex_nodes::Regions>(regions()));
  apex::Regions read;
  ros::serialization::IStream stream(const_cast<std::uint8_t*>(s.bytes.data()), static_cast<std::uint32_t>(s.bytes.size()));
  ros::serialization::deserialize(stream, read);
  EXPECT_EQ(read, apex_nodes::toRos(regions()));
  EXPECT_THAT(apex::inspectedTypes(), testing::IsSupersetOf({"apex_nodes/Regions", "apex_nodes/Keypoints", "apex_nodes/Image"}));
}

std::string errorOf(Graph& g, const std::string& node) {
  for (const auto& s : g.nodeStats())
    if (s.name == node) return s.error;
  return "no node '" + node + "'";
}

TEST(RosResults, BagWriterRecordsRegionsAtTheirStampAndTheyReadBackThroughFromRos) {
  const fs::path dir = bagDirectory() / "ros_results";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string out = (dir / "regions.bag").string();
  {
    Graph g(pluginRegistry());
    add(g, "apex_nodes/BagWriter", "rec");
    ASSERT_TRUE(g.setParameter("rec", "topics", "[/regions]"));
    ASSERT_TRUE(g.setParameter("rec", "file", out));
    add(g, "test/MessageFeeder", "feed");
    link(g, "feed", "out", "rec", "regions");
    g.start();
    object<MessageFeeder>(g, "feed")->feed(apex::Message::make<apex_nodes::Regions>(regions()));
    ASSERT_TRUE(g.waitIdle(kWait));
    ASSERT_TRUE(g.fireSlot("rec", "stop"));
    // read once it is closed (renamed): see test_bag_writer
    ASSERT_TRUE(waitUntil([&] { return fs::exists(out) && !fs::exists(out + ".active"); }));
    EXPECT_EQ(errorOf(g, "rec"), "");
  }
  rosbag::Bag bag(out, rosbag::bagmode::Read);
  std::vector<rosbag::MessageInstance> got;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/regions"))) got.push_back(m);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].getDataType(), "apex/Regions");
  EXPECT_EQ(got[0].getTime(), header().stamp);
  const auto msg = got[0].instantiate<apex::Regions>();
  ASSERT_TRUE(msg);
  const apex_nodes::Regions back = apex_nodes::fromRos(*msg);
  ASSERT_EQ(back.regions.size(), 2u);
  EXPECT_EQ(back.regions[0].box, cv::Rect(10, 20, 30, 40));
  EXPECT_EQ(back.regions[0].label, 3);
  EXPECT_EQ(back.image_size, cv::Size(640, 480));
}

TEST(ResultPublisher, ATypeWithNoRosFormIsAnErrorNamingItAndTheTypesThatHaveOne) {
  Graph g(pluginRegistry());
  add(g, "apex_nodes/ResultPublisher", "pub");
  add(g, "test/MessageFeeder", "feed");
  link(g, "feed", "out", "pub", "in");
  g.start();
  object<MessageFeeder>(g, "feed")->feed(apex::Message::make<NoRosForm>({}));
  ASSERT_TRUE(waitUntil([&] { return !errorOf(g, "pub").empty(); }));
  const std::string error = errorOf(g, "pub");
  EXPECT_THAT(error, HasSubstr("test/NoRosForm has no ROS form to publish; these types have one: "));
  for (const char* type : {"apex_nodes/Regions", "apex_nodes/Contours", "apex_nodes/Keypoints", "apex_nodes/Matches",
                           "apex_nodes/Image", "apex_nodes/Cloud", "int"})
    EXPECT_THAT(error, HasSubstr(type));
  EXPECT_THAT(error, testing::Not(HasSubstr("NoRosForm,")));  // only those that have one
}

TEST(MarkerPublisher, KeypointsArePointsOnTheirRaysAtRayLength) {
  sensor_msgs::CameraInfo camera;
  camera.header.frame_id = "camera";
  camera.P = {500, 0, 320, 0, 0, 400, 240, 0, 0, 0, 1, 0};
  apex_nodes::Keypoints k = keypoints(CV_8U);
  k.keypoints = {cv::KeyPoint(320.f, 240.f, 1.f), cv::KeyPoint(820.f, 40.f, 1.f)};
  apex_nodes::MarkerOptions options;
  options.ns = "seen";
  options.ray_length = 2.0;
  const visualization_msgs::Marker m = apex_nodes::keypointPoints(k, camera, options);
  EXPECT_EQ(m.header.frame_id, "camera");
  EXPECT_EQ(m.header.stamp, header().stamp);
  EXPECT_EQ(m.ns, "seen/keypoints");
  EXPECT_EQ(m.type, visualization_msgs::Marker::POINTS);
  ASSERT_EQ(m.points.size(), 2u);
  EXPECT_EQ(m.points[0].x, 0.0);  // the principal point: on the optical axis
  EXPECT_EQ(m.points[0].y, 0.0);
  EXPECT_EQ(m.points[0].z, 2.0);
  EXPECT_DOUBLE_EQ(m.points[1].x, 2.0);  // (820 - 320) / 500 * 2
  EXPECT_DOUBLE_EQ(m.points[1].y, -1.0);  // (40 - 240) / 400 * 2
  EXPECT_EQ(m.points[1].z, 2.0);
  camera.P = {};
  EXPECT_THROW(apex_nodes::keypointPoints(k, camera, options), std::invalid_argument);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::Time::init();
  return RUN_ALL_TESTS();
}
