// TfLookup finds the transform at each message's stamp; a missing frame is a
// named error while the graph keeps running. MergeClouds moves clouds by tf2;
// LaserProjector moves each reading of a scan by tf2 at its own time.
#include <apex/AddNode.h>
#include <apex/Connect.h>
#include <apex/GraphState.h>
#include <apex/Inspect.h>
#include <apex/SetParameter.h>
#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <gmock/gmock.h>
#include <laser_geometry/laser_geometry.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2/buffer_core.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "apex_test/ros_client.hpp"

using namespace apex_test;
using ::testing::HasSubstr;

namespace {

std::string g_bag;

void add(const std::string& type, const std::string& name, const std::string& params) {
  apex::AddNode::Request r;
  r.type = type, r.name = name, r.parameters = params;
  auto res = call<apex::AddNode>("add_node", r);
  ASSERT_TRUE(res.success) << res.message;
}

void link(const std::string& a, const std::string& ap, const std::string& b, const std::string& bp) {
  apex::Connect::Request r;
  r.from_node = a, r.from_port = ap, r.to_node = b, r.to_port = bp;
  auto res = call<apex::Connect>("connect", r);
  ASSERT_TRUE(res.success) << res.message;
}

TEST(Tf, LookupAtTheMessageStamp) {
  tf2_ros::StaticTransformBroadcaster broadcaster;
  geometry_msgs::TransformStamped t;
  t.header.frame_id = "base_link";
  t.child_frame_id = "camera";  // the demo bag's frame
  t.transform.translation.z = 1.25;
  t.transform.rotation.w = 1.0;
  broadcaster.sendTransform(t);

  add("apex_nodes/BagReader", "bag", "{file: '" + g_bag + "', rate: 0, loop: true, playing: false}");
  add("apex_nodes/TfLookup", "tf", "{target_frame: base_link, timeout: 2.0}");
  link("bag", "image", "tf", "stamped");
  apex::Inspect::Request inspect;
  inspect.node = "tf", inspect.port = "transform", inspect.enable = true;
  auto topic = call<apex::Inspect>("inspect", inspect);
  ASSERT_TRUE(topic.success) << topic.message;
  EXPECT_EQ(topic.message_type, "geometry_msgs/TransformStamped");
  apex::SetParameter::Request play;
  play.node = "bag", play.parameter = "playing", play.value = "true";
  ASSERT_TRUE(call<apex::SetParameter>("set_parameter", play).success);

  ros::NodeHandle nh;
  geometry_msgs::TransformStamped got;
  ASSERT_TRUE(receive(nh, topic.topic, got));
  EXPECT_EQ(got.header.frame_id, "base_link");
  EXPECT_EQ(got.child_frame_id, "camera");
  EXPECT_DOUBLE_EQ(got.transform.translation.z, 1.25);

  apex::SetParameter::Request missing;
  missing.node = "tf", missing.parameter = "target_frame", missing.value = "nowhere";
  ASSERT_TRUE(call<apex::SetParameter>("set_parameter", missing).success);
  missing.parameter = "timeout", missing.value = "0.05";
  ASSERT_TRUE(call<apex::SetParameter>("set_parameter", missing).success);
  apex::GraphState graph;
  for (int i = 0; i < 40; ++i) {  // each ~graph update; the error shows within a few frames
    ASSERT_TRUE(receive(nh, "/apex/graph", graph));
    if (!graph.nodes.at(1).error.empty()) break;
  }
  EXPECT_THAT(graph.nodes.at(1).error, HasSubstr("no transform camera -> nowhere"));
  EXPECT_TRUE(keepsFiring(nh, "bag"));
}

TEST(Laser, ASubscribedScanReachesTheGraph) {
  add("apex_nodes/LaserScanSubscriber", "laser", "{topic: /test_scan}");
  apex::Inspect::Request inspect;
  inspect.node = "laser", inspect.port = "scan", inspect.enable = true;
  auto topic = call<apex::Inspect>("inspect", inspect);
  ASSERT_TRUE(topic.success) << topic.message;
  EXPECT_EQ(topic.message_type, "sensor_msgs/LaserScan");
  ros::NodeHandle nh;
  auto pub = nh.advertise<sensor_msgs::LaserScan>("/test_scan", 1);
  sensor_msgs::LaserScan scan;
  scan.header.frame_id = "laser";
  scan.ranges = {1.f, 2.f, 3.f};
  // a sensor keeps publishing; the first scans may pass before every connection stands
  auto sensor = nh.createWallTimer(ros::WallDuration(0.05), [&](const ros::WallTimerEvent&) { pub.publish(scan); });
  sensor_msgs::LaserScan got;
  ASSERT_TRUE(receive(nh, topic.topic, got));
  EXPECT_EQ(got.header.frame_id, "laser");
  EXPECT_EQ(got.ranges, scan.ranges);
}

TEST(Tf, MergeCloudsMovesEachCloudAtItsStamp) {
  tf2_ros::StaticTransformBroadcaster broadcaster;  // latched: the new node's listener receives it
  geometry_msgs::TransformStamped t;
  t.header.frame_id = "base_link";
  t.child_frame_id = "camera";  // the demo bag's clouds
  t.transform.translation.z = 1.25;
  t.transform.rotation.w = 1.0;
  broadcaster.sendTransform(t);

  add("apex_nodes/BagReader", "clouds", "{file: '" + g_bag + "', rate: 0, loop: true, playing: false}");
  add("apex_nodes/MergeClouds", "merge", "{frame: base_link, timeout: 2.0}");
  link("clouds", "cloud", "merge", "cloud_0");
  link("clouds", "cloud", "merge", "cloud_1");
  apex::Inspect::Request inspect;
  inspect.node = "merge", inspect.port = "cloud", inspect.enable = true;
  auto topic = call<apex::Inspect>("inspect", inspect);
  ASSERT_TRUE(topic.success) << topic.message;
  EXPECT_EQ(topic.message_type, "sensor_msgs/PointCloud2");
  apex::SetParameter::Request play;
  play.node = "clouds", play.parameter = "playing", play.value = "true";
  ASSERT_TRUE(call<apex::SetParameter>("set_parameter", play).success);

  ros::NodeHandle nh;
  sensor_msgs::PointCloud2 got;
  ASSERT_TRUE(receive(nh, topic.topic, got));
  EXPECT_EQ(got.header.frame_id, "base_link");
  EXPECT_EQ(std::size_t(got.width) * got.height, 2 * 18000u);  // the bag's cloud, twice
  float low = 1e9f;
  for (sensor_msgs::PointCloud2ConstIterator<float> z(got, "z"); z != z.end(); ++z) low = std::min(low, *z);
  EXPECT_NEAR(low, 0.3 + 1.25, 0.01);  // the floor starts 0.3 m ahead of the camera: 1.25 m up
}

/** A laser's half turn in a corridor (3 m ahead, 1.5 m to each side), a reading a degree swept in 50 ms;
 *  every 13th reading no return. */
sensor_msgs::LaserScan sweep(const ros::Time& stamp) {
  sensor_msgs::LaserScan s;
  s.header.frame_id = "laser";
  s.header.stamp = stamp;
  s.angle_min = float(-M_PI / 2);
  s.angle_increment = float(M_PI / 180);
  s.angle_max = s.angle_min + 180 * s.angle_increment;
  s.time_increment = 0.05f / 180, s.scan_time = 0.1f;
  s.range_min = 0.1f, s.range_max = 10.f;
  for (int i = 0; i <= 180; ++i) {
    const double a = s.angle_min + i * double(s.angle_increment), c = std::cos(a), d = std::abs(std::sin(a));
    const double wall = std::min(c > 1e-9 ? 3.0 / c : 1e9, d > 1e-9 ? 1.5 / d : 1e9);
    s.ranges.push_back(i % 13 ? float(wall) : std::numeric_limits<float>::infinity());
    s.intensities.push_back(float(100 + i));
  }
  return s;
}

/** base_link -> laser at `stamp`: the laser `x` m ahead and turned `yaw` (a little roll and pitch). */
geometry_msgs::TransformStamped laserPose(const ros::Time& stamp, double x, double yaw) {
  geometry_msgs::TransformStamped t;
  t.header.frame_id = "base_link";
  t.header.stamp = stamp;
  t.child_frame_id = "laser";
  t.transform.translation.x = x, t.transform.translation.y = -0.1, t.transform.translation.z = 0.4;
  tf2::Quaternion q;
  q.setRPY(0.02, -0.03, yaw);
  t.transform.rotation.x = q.x(), t.transform.rotation.y = q.y(), t.transform.rotation.z = q.z(), t.transform.rotation.w = q.w();
  return t;
}

/** The x and y of a cloud's points, in order. */
std::vector<std::pair<float, float>> planar(const sensor_msgs::PointCloud2& c) {
  std::vector<std::pair<float, float>> out;
  for (sensor_msgs::PointCloud2ConstIterator<float> x(c, "x"), y(c, "y"); x != x.end(); ++x, ++y) out.emplace_back(*x, *y);
  return out;
}

float apart(const std::pair<float, float>& a, const std::pair<float, float>& b) {
  return std::hypot(a.first - b.first, a.second - b.second);
}

TEST(Tf, LaserProjectorMovesEachReadingAtItsOwnTime) {
  // the laser turns 0.45 rad and moves 0.15 m ahead from 50 ms before the scan to 100 ms after it:
  // tf2 interpolates the transforms at the first and the last reading, laser_geometry each reading's
  const sensor_msgs::LaserScan scan = sweep(ros::Time(1000, 0));
  tf2_msgs::TFMessage poses;
  poses.transforms = {laserPose(scan.header.stamp - ros::Duration(0.05), 0.30, 0.10),
                      laserPose(scan.header.stamp + ros::Duration(0.10), 0.45, 0.55)};
  tf2::BufferCore buffer;  // the same transforms for the direct call
  for (const auto& t : poses.transforms) ASSERT_TRUE(buffer.setTransform(t, "test"));
  namespace channel = laser_geometry::channel_option;
  const int channels = channel::Default | channel::Distance | channel::Timestamp;
  sensor_msgs::PointCloud2 want;
  laser_geometry::LaserProjection().transformLaserScanToPointCloud("base_link", scan, want, buffer, -1.0, channels);
  // each reading's time matters: the whole scan moved as at its first reading puts the last elsewhere
  sensor_msgs::LaserScan instant = scan;
  instant.time_increment = 0;
  sensor_msgs::PointCloud2 rigid;
  laser_geometry::LaserProjection().transformLaserScanToPointCloud("base_link", instant, rigid, buffer, -1.0, channels);
  const auto moving = planar(want), still = planar(rigid);
  ASSERT_EQ(moving.size(), still.size());
  ASSERT_GT(moving.size(), 150u);
  EXPECT_LT(apart(moving.front(), still.front()), 0.01);  // reading 1: 0.3 ms after the stamp
  EXPECT_GT(apart(moving.back(), still.back()), 0.1);  // reading 180: 50 ms after

  // latched on /tf: the node's listener gets them once, whenever it connects (sent again, tf2 would
  // refuse the same stamps with an error each time)
  ros::NodeHandle nh;
  ros::Publisher moves = nh.advertise<tf2_msgs::TFMessage>("/tf", 1, true);
  moves.publish(poses);
  add("apex_nodes/LaserScanSubscriber", "sweeps", "{topic: /test_sweep}");
  add("apex_nodes/LaserProjector", "projector", "{target_frame: base_link, timeout: 2.0, distance: true, timestamp: true}");
  link("sweeps", "scan", "projector", "scan");
  apex::Inspect::Request inspect;
  inspect.node = "projector", inspect.port = "cloud", inspect.enable = true;
  auto topic = call<apex::Inspect>("inspect", inspect);
  ASSERT_TRUE(topic.success) << topic.message;
  EXPECT_EQ(topic.message_type, "sensor_msgs/PointCloud2");
  auto pub = nh.advertise<sensor_msgs::LaserScan>("/test_sweep", 1);
  auto sensor = nh.createWallTimer(ros::WallDuration(0.05), [&](const ros::WallTimerEvent&) { pub.publish(scan); });
  sensor_msgs::PointCloud2 got;
  ASSERT_TRUE(receive(nh, topic.topic, got));
  EXPECT_EQ(got.header.frame_id, "base_link");
  EXPECT_EQ(got.header.stamp, scan.header.stamp);
  EXPECT_EQ(got.width, want.width);
  EXPECT_EQ(got.height, want.height);
  EXPECT_EQ(got.point_step, want.point_step);
  EXPECT_EQ(got.row_step, want.row_step);
  EXPECT_EQ(got.is_dense, want.is_dense);
  EXPECT_EQ(got.fields, want.fields);  // x y z intensity index distances stamps, at laser_geometry's offsets
  EXPECT_TRUE(got.data == want.data) << "the points' bytes differ";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_tf");
  if (argc < 2) return 2;
  g_bag = argv[1];
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
