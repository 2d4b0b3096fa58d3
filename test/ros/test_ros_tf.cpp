// TfLookup finds the transform at each message's stamp; a missing frame is a
// named error while the graph keeps running. MergeClouds moves clouds by tf2.
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
#include <tf2_ros/static_transform_broadcaster.h>

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
