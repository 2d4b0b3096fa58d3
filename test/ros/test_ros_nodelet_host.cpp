// NodeletHost with Debian's own nodelets, against APEX's nodes on the same data: image_proc's
// rectify on opencv-doc's left01.jpg with its calibration equals APEX's Rectify; pcl_ros's
// VoxelGrid on a generated cloud equals APEX's VoxelGrid with the same leaf. A plugin that is not
// declared, and a frame the nodelet does not answer, are errors naming it; removing the node
// leaves no topic and no thread behind. Needs a ROS master (nodelet_host.test).
#include <gmock/gmock.h>
#include <pcl/conversions.h>
#include <pcl/point_types.h>
#include <pcl_conversions/pcl_conversions.h>
#include <ros/ros.h>

#include <filesystem>
#include <opencv2/core/persistence.hpp>
#include <random>
#include <set>

#include "apex_nodes/types.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;
using apex_nodes::Cloud;
using apex_nodes::Image;
using sensor_msgs::CameraInfo;
using ::testing::HasSubstr;

namespace {

using Points = pcl::PointCloud<pcl::PointXYZ>;

/** opencv-doc's left01.jpg, bgr8, stamped `stamp` on frame left_camera. */
std::shared_ptr<const Image> leftImage(const ros::Time& stamp = ros::Time(42, 7)) {
  auto image = std::make_shared<Image>(*readDataImage("left01.jpg", "left_camera"));
  image->header.stamp = stamp;
  return image;
}

/** Its camera model from left_intrinsics.yml (OpenCV's format), stamped as the image. */
std::shared_ptr<const CameraInfo> leftModel(const Image& image) {
  cv::FileStorage fs(kOpenCvData + "/left_intrinsics.yml", cv::FileStorage::READ);
  cv::Mat K, D;
  fs["camera_matrix"] >> K;
  fs["distortion_coefficients"] >> D;
  auto info = std::make_shared<CameraInfo>();
  info->header = image.header;
  info->width = image.mat.cols, info->height = image.mat.rows, info->distortion_model = "plumb_bob";
  std::copy(K.begin<double>(), K.end<double>(), info->K.begin());
  info->D.assign(D.begin<double>(), D.end<double>());
  info->R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) info->P[r * 4 + c] = info->K[r * 3 + c];
  return info;
}

std::vector<Message> cameraFrame(const std::shared_ptr<const Image>& image, const std::shared_ptr<const CameraInfo>& info) {
  return {Message::share<Image>(image), Message::share<CameraInfo>(info)};
}

/** 5000 points in the cube [-1, 1]^3 (a fixed seed), stamped to the nanosecond. */
std::shared_ptr<const Cloud> generatedCloud() {
  Points points;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  for (int i = 0; i < 5000; ++i) points.push_back(pcl::PointXYZ(u(rng), u(rng), u(rng)));
  auto blob = std::make_shared<pcl::PCLPointCloud2>();
  pcl::toPCLPointCloud2(points, *blob);
  auto cloud = std::make_shared<Cloud>();
  cloud->header.frame_id = "velodyne";
  cloud->header.stamp = ros::Time(1700000000, 123456789);
  cloud->points = blob;
  return cloud;
}

Points pointsOf(const Cloud& cloud) {
  Points out;
  pcl::fromPCLPointCloud2(*cloud.points, out);
  return out;
}

/** pcl/VoxelGrid in a NodeletHost: `config` sets its leaf (and no z limits: its default keeps 0 <= z <= 1). */
const std::vector<std::pair<std::string, std::string>> kVoxelGrid{{"nodelet", "pcl/VoxelGrid"},
                                                                  {"inputs", "[input:sensor_msgs/PointCloud2]"},
                                                                  {"outputs", "[output:sensor_msgs/PointCloud2]"},
                                                                  {"config", "\"{leaf_size: 0.1, filter_field_name: ''}\""},
                                                                  {"timeout", "10"}};
/** A frame's answer is waited for up to 10 s (the node's default, 1 s, a loaded machine can miss). */
const std::vector<std::pair<std::string, std::string>> kPatient{{"timeout", "10"}};

/** APEX's VoxelGrid on `cloud` with `leaf`. */
Points apexVoxelGrid(const std::shared_ptr<const Cloud>& cloud, double leaf) {
  NodeHarness h("apex_nodes/VoxelGrid", {"cloud"}, "cloud", {{"leaf_size", std::to_string(leaf)}});
  const Message m = h.run(cloud);
  EXPECT_TRUE(m.as<Cloud>()) << h.error();
  return m.as<Cloud>() ? pointsOf(*m.as<Cloud>()) : Points();
}

void expectSamePoints(const Points& got, const Points& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    // Both sum each voxel's points in float in the same order (PCL's typed and field-generic
    // VoxelGrid sort the same voxel indices): equal, not merely close.
    ASSERT_EQ(got[i].x, want[i].x) << i;
    ASSERT_EQ(got[i].y, want[i].y) << i;
    ASSERT_EQ(got[i].z, want[i].z) << i;
  }
}

std::size_t threadCount() {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& task : std::filesystem::directory_iterator("/proc/self/task")) ++n;
  return n;
}

/** Every topic this process subscribes to or advertises. */
std::set<std::string> ourTopics() {
  ros::V_string subscribed, advertised;
  ros::this_node::getSubscribedTopics(subscribed);
  ros::this_node::getAdvertisedTopics(advertised);
  std::set<std::string> out(subscribed.begin(), subscribed.end());
  out.insert(advertised.begin(), advertised.end());
  return out;
}

std::vector<std::string> nodeletTopics() {
  std::vector<std::string> out;
  for (const auto& t : ourTopics())
    if (t.find("/nodelets/") != std::string::npos) out.push_back(t);
  return out;
}

TEST(NodeletHost, ImageProcRectifyEqualsApexsRectifyAndKeepsTheFramesHeader) {
  // its defaults: image_proc/rectify
  NodeHarness host("apex_nodes/NodeletHost", {"image_mono", "camera_info"}, "image_rect", kPatient);
  NodeHarness apex("apex_nodes/Rectify", {"image", "camera_info"}, "image");
  for (int frame = 0; frame < 3; ++frame) {
    const auto image = leftImage(ros::Time(42 + frame, 7));
    const auto info = leftModel(*image);
    const Message got = host.run(cameraFrame(image, info));
    const Message want = apex.run(cameraFrame(image, info));
    ASSERT_TRUE(got.as<Image>()) << "frame " << frame << ": " << host.error();
    ASSERT_TRUE(want.as<Image>()) << apex.error();
    EXPECT_EQ(got.as<Image>()->header, image->header);  // image_proc keeps the frame's header
    EXPECT_EQ(got.as<Image>()->encoding, "bgr8");
    // Both are image_geometry's rectifyImage with linear interpolation (image_proc's default).
    expectSameMat(got.as<Image>()->mat, want.as<Image>()->mat);
    EXPECT_GT(cv::norm(got.as<Image>()->mat, image->mat, cv::NORM_L1) / image->mat.total(), 5.0);  // undistorted
  }
}

TEST(NodeletHost, PclRosVoxelGridEqualsApexsVoxelGridWithTheSameLeaf) {
  const auto cloud = generatedCloud();
  NodeHarness host("apex_nodes/NodeletHost", {"input"}, "output", kVoxelGrid);
  const Message got = host.run(cloud);
  ASSERT_TRUE(got.as<Cloud>()) << host.error();
  EXPECT_EQ(got.as<Cloud>()->header, cloud->header);  // pcl_ros copies the stamp, to the nanosecond
  const Points want = apexVoxelGrid(cloud, 0.1);
  EXPECT_GT(want.size(), 1000u);
  EXPECT_LT(want.size(), 5000u);
  expectSamePoints(pointsOf(*got.as<Cloud>()), want);

  // A new config reloads the nodelet with it.
  host.set("config", "\"{leaf_size: 0.25, filter_field_name: ''}\"");
  const Message coarser = host.run(cloud);
  ASSERT_TRUE(coarser.as<Cloud>()) << host.error();
  expectSamePoints(pointsOf(*coarser.as<Cloud>()), apexVoxelGrid(cloud, 0.25));
}

// A nodelet that publishes on its own, fed by a topic of the ROS graph: a source of the graph.
TEST(NodeletSource, SendsWhatTheNodeletPublishesFromATopic) {
  const auto cloud = generatedCloud();
  auto params = kVoxelGrid;
  params.erase(params.begin() + 1);  // no inputs: its input is a topic
  params.pop_back();  // nor a frame's timeout: it sends what the nodelet publishes, when it does
  params.push_back({"remap", "[\"input:=/nodelet_host_test/points\"]"});
  NodeHarness source("apex_nodes/NodeletSource", {}, "output", params);
  auto* sink = object<Collector>(source.graph(), "sink");
  sensor_msgs::PointCloud2 msg;
  pcl_conversions::fromPCL(*cloud->points, msg);
  msg.header = cloud->header;
  ros::NodeHandle nh;
  auto pub = nh.advertise<sensor_msgs::PointCloud2>("/nodelet_host_test/points", 1);
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);  // bounds a hang only
  while (!sink->waitFor(1, 0.05) && std::chrono::steady_clock::now() < until)
    pub.publish(msg);  // until the nodelet has subscribed
  ASSERT_TRUE(sink->waitFor(1, 0.05)) << "the source sent nothing: " << source.error();
  const Message got = sink->messages().front();
  ASSERT_TRUE(got.as<Cloud>()) << source.error();
  EXPECT_EQ(got.as<Cloud>()->header, cloud->header);
  expectSamePoints(pointsOf(*got.as<Cloud>()), apexVoxelGrid(cloud, 0.1));
}

TEST(NodeletHost, APluginNobodyDeclaresIsAnErrorNamingItAndTheClosestOnes) {
  NodeHarness host("apex_nodes/NodeletHost", {"image_mono", "camera_info"}, "image_rect", {{"nodelet", "image_proc/rectfy"}});
  const auto image = leftImage();
  expectNothing(host, host.run(cameraFrame(image, leftModel(*image))), "no nodelet plugin 'image_proc/rectfy' is declared");
  EXPECT_THAT(host.error(), HasSubstr("did you mean image_proc/rectify?"));
}

TEST(NodeletHost, AFrameWithoutAnAnswerIsNothingAndAnErrorNamingTheNodeletAndTheOutput) {
  NodeHarness host("apex_nodes/NodeletHost", {"image_mono", "camera_info"}, "image_rect", {{"timeout", "0.3"}});
  const auto image = leftImage();
  auto uncalibrated = std::make_shared<CameraInfo>(*leftModel(*image));
  uncalibrated->K = {};  // image_proc says so in its log and publishes nothing
  const Message none = host.run(cameraFrame(image, uncalibrated));
  expectNothing(host, none, "nodelet 'image_proc/rectify'");
  EXPECT_THAT(host.error(), HasSubstr("did not answer within"));
  EXPECT_THAT(host.error(), HasSubstr("no 'image_rect'"));

  host.set("timeout", "10");  // the next frame is answered (a deadline that only bounds a hang: a loaded machine is slow)
  const auto next = leftImage(ros::Time(43, 0));
  const Message got = host.run(cameraFrame(next, leftModel(*next)));
  ASSERT_TRUE(got.as<Image>()) << host.error();
  EXPECT_EQ(got.as<Image>()->header, next->header);
}

TEST(NodeletHost, RemovingTheNodeLeavesNoTopicNoParameterAndNoThread) {
  const auto cloud = generatedCloud();
  const auto image = leftImage();
  auto runBoth = [&](std::vector<std::string>* loaded) {
    NodeHarness voxels("apex_nodes/NodeletHost", {"input"}, "output", kVoxelGrid);
    NodeHarness rectify("apex_nodes/NodeletHost", {"image_mono", "camera_info"}, "image_rect", kPatient);
    EXPECT_TRUE(voxels.run(cloud).as<Cloud>()) << voxels.error();
    EXPECT_TRUE(rectify.run(cameraFrame(image, leftModel(*image))).as<Image>()) << rectify.error();
    if (loaded) *loaded = nodeletTopics();
  };
  runBoth(nullptr);  // first loads: the libraries, roscpp's timer thread (pcl_ros's lazy subscriber starts a timer)
  const std::size_t threads = threadCount();
  const auto topics = ourTopics();
  std::vector<std::string> loaded;
  runBoth(&loaded);
  // Both nodes are named "node" (in two graphs): one nodelet is .../nodelets/node, the other node_2.
  EXPECT_THAT(loaded, ::testing::Contains(::testing::EndsWith("/input")));
  EXPECT_THAT(loaded, ::testing::Contains(::testing::EndsWith("/image_mono")));
  EXPECT_THAT(nodeletTopics(), ::testing::IsEmpty());
  EXPECT_EQ(ourTopics(), topics);
  EXPECT_EQ(threadCount(), threads);
  EXPECT_FALSE(ros::param::has(ros::this_node::getName() + "/nodelets/node"));  // its config went with it
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_nodelet_host");
  ros::NodeHandle nh;  // the node runs while the tests do
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
