// Sensors through the runtime, as a user's robot sends them. A lidar's sensor_msgs/PointCloud2
// (x, y, z, intensity): what PassThrough and VoxelGrid publish keeps the intensity of each
// point, every field, the frame and the stamp to the nanosecond. A camera's images with their
// camera_info (opencv-doc's real calibration): rectified as OpenCV's remap does, published with
// the model, on the frame's stamp.
#include <apex/ChessboardCorners.h>
#include <gmock/gmock.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_types.h>
#include <pcl_conversions/pcl_conversions.h>
#include <cv_bridge/cv_bridge.h>
#include <image_transport/image_transport.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <visualization_msgs/MarkerArray.h>

#include <condition_variable>
#include <mutex>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace {

using Lidar = pcl::PointCloud<pcl::PointXYZI>;

/** 20 x 25 points, one metre away, intensity = index. */
Lidar lidarPoints() {
  Lidar points;
  for (int i = 0; i < 500; ++i) points.push_back(pcl::PointXYZI(0.01f * (i % 20), 0.01f * (i / 20), 1.f, float(i)));
  return points;
}

sensor_msgs::PointCloud2 lidarMessage() {
  sensor_msgs::PointCloud2 m;
  pcl::toROSMsg(lidarPoints(), m);
  m.header.frame_id = "velodyne";
  m.header.stamp = ros::Time(1700000000, 123456789);
  return m;
}

/** Sends the cloud every 50 ms until a message arrives on `topic` (the runtime may still be
 *  subscribing), or 30 s pass. */
template <class Msg = sensor_msgs::PointCloud2>
boost::shared_ptr<const Msg> sendAndReceive(const std::string& topic) {
  ros::NodeHandle nh;
  std::mutex m;
  std::condition_variable arrived;
  boost::shared_ptr<const Msg> got;
  auto sub = nh.subscribe<Msg>(topic, 1, [&](const boost::shared_ptr<const Msg>& msg) {
    std::lock_guard<std::mutex> l(m);
    got = msg;
    arrived.notify_all();
  });
  auto pub = nh.advertise<sensor_msgs::PointCloud2>("/clouds/in", 1);
  const auto message = lidarMessage();
  for (auto deadline = ros::WallTime::now() + ros::WallDuration(30); ros::WallTime::now() < deadline;) {
    pub.publish(message);
    std::unique_lock<std::mutex> l(m);
    if (arrived.wait_for(l, std::chrono::milliseconds(50), [&] { return got != nullptr; })) return got;
  }
  return nullptr;
}

std::vector<std::string> fieldNames(const sensor_msgs::PointCloud2& m) {
  std::vector<std::string> out;
  for (const auto& f : m.fields) out.push_back(f.name);
  return out;
}

TEST(Clouds, PassThroughKeepsEachPointsIntensityFrameAndStamp) {
  auto got = sendAndReceive("/clouds/near");
  ASSERT_TRUE(got) << "nothing on /clouds/near";
  EXPECT_EQ(got->header.frame_id, "velodyne");
  EXPECT_EQ(got->header.stamp, ros::Time(1700000000, 123456789));
  EXPECT_THAT(fieldNames(*got), ::testing::ElementsAre("x", "y", "z", "intensity"));
  Lidar near;
  pcl::fromROSMsg(*got, near);
  ASSERT_EQ(near.size(), 250u);  // x = 0.00 .. 0.09 of each row of 20
  for (std::size_t k = 0; k < near.size(); ++k) ASSERT_EQ(near[k].intensity, float((k / 10) * 20 + k % 10)) << k;
}

TEST(Clouds, TheClustersBoxGoesToRvizAsAMarker) {
  auto got = sendAndReceive<visualization_msgs::MarkerArray>("/clouds/boxes");
  ASSERT_TRUE(got) << "nothing on /clouds/boxes";
  std::vector<visualization_msgs::Marker> boxes;
  for (const auto& m : got->markers)
    if (m.type == visualization_msgs::Marker::CUBE) boxes.push_back(m);
  ASSERT_EQ(boxes.size(), 1u);  // the lidar's one sheet of points
  EXPECT_EQ(boxes[0].header.frame_id, "velodyne");
  EXPECT_NEAR(boxes[0].scale.x, 0.19, 1e-5);  // x 0.00 .. 0.19
  EXPECT_NEAR(boxes[0].scale.y, 0.24, 1e-5);  // y 0.00 .. 0.24
  EXPECT_NEAR(boxes[0].pose.position.z, 1.0, 1e-5);
}

TEST(Clouds, VoxelGridAveragesIntensityAsPclDoes) {
  auto got = sendAndReceive("/clouds/voxels");
  ASSERT_TRUE(got) << "nothing on /clouds/voxels";
  EXPECT_EQ(got->header.stamp, ros::Time(1700000000, 123456789));
  pcl::VoxelGrid<pcl::PointXYZI> f;
  f.setInputCloud(std::make_shared<Lidar>(lidarPoints()));
  f.setLeafSize(0.05f, 0.05f, 0.05f);
  Lidar want, voxels;
  f.filter(want);
  pcl::fromROSMsg(*got, voxels);
  ASSERT_EQ(voxels.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(voxels[i].x, want[i].x) << i;
    ASSERT_EQ(voxels[i].intensity, want[i].intensity) << i;
  }
}

const std::string kData = "/usr/share/doc/opencv-doc/examples/data";  // scripts/install_deps installs opencv-doc

/** opencv-doc's left01.jpg with its calibration (left_intrinsics.yml), as a camera sends them. */
struct LeftCamera {
  cv::Mat raw, K, D;
  sensor_msgs::ImagePtr image;
  sensor_msgs::CameraInfo info;
};

LeftCamera leftCamera(const ros::Time& stamp) {
  LeftCamera cam;
  cam.raw = cv::imread(kData + "/left01.jpg", cv::IMREAD_COLOR);
  if (cam.raw.empty()) ADD_FAILURE() << "cannot read left01.jpg: is opencv-doc installed?";
  cv::FileStorage fs(kData + "/left_intrinsics.yml", cv::FileStorage::READ);
  fs["camera_matrix"] >> cam.K;
  fs["distortion_coefficients"] >> cam.D;
  sensor_msgs::CameraInfo& info = cam.info;
  info.width = cam.raw.cols, info.height = cam.raw.rows, info.distortion_model = "plumb_bob";
  std::copy(cam.K.begin<double>(), cam.K.end<double>(), info.K.begin());
  info.D.assign(cam.D.begin<double>(), cam.D.end<double>());
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) info.P[r * 4 + c] = info.K[r * 3 + c];
  info.header.frame_id = "left_camera", info.header.stamp = stamp;
  cam.image = cv_bridge::CvImage(info.header, "bgr8", cam.raw).toImageMsg();
  return cam;
}

/** Sends the camera's frame on /camera/image_raw until `received()` (under `m`; the subscriber's
 *  callback notifies `arrived`), again after each 50 ms without it, for up to 30 s. */
template <class Received>
void sendUntil(const LeftCamera& cam, std::mutex& m, std::condition_variable& arrived, Received received) {
  ros::NodeHandle nh;
  image_transport::ImageTransport it(nh);
  auto pub = it.advertiseCamera("/camera/image_raw", 1);
  for (auto deadline = ros::WallTime::now() + ros::WallDuration(30); ros::WallTime::now() < deadline;) {
    pub.publish(*cam.image, cam.info);  // again until it arrives: the runtime may not be subscribed yet
    std::unique_lock<std::mutex> l(m);
    if (arrived.wait_for(l, std::chrono::milliseconds(50), received)) return;
  }
}

TEST(Camera, ImagesAreRectifiedByTheirCameraInfoAndPublishedWithIt) {
  const LeftCamera cam = leftCamera(ros::Time(1700000000, 987654321));
  ros::NodeHandle nh;
  image_transport::ImageTransport it(nh);
  std::mutex m;
  std::condition_variable arrived;
  sensor_msgs::ImageConstPtr got_image;
  sensor_msgs::CameraInfoConstPtr got_info;
  auto sub = it.subscribeCamera("/camera/image_rect", 1,
                                [&](const sensor_msgs::ImageConstPtr& i, const sensor_msgs::CameraInfoConstPtr& c) {
                                  std::lock_guard<std::mutex> l(m);
                                  got_image = i, got_info = c;
                                  arrived.notify_all();
                                });
  sendUntil(cam, m, arrived, [&] { return got_image != nullptr; });
  std::lock_guard<std::mutex> l(m);
  ASSERT_TRUE(got_image) << "nothing on /camera/image_rect";
  EXPECT_EQ(got_image->header.stamp, cam.info.header.stamp);
  EXPECT_EQ(got_info->header.stamp, cam.info.header.stamp);
  EXPECT_EQ(got_info->K, cam.info.K);
  cv::Mat map1, map2, want;
  cv::initUndistortRectifyMap(cam.K, cam.D, cv::Mat::eye(3, 3, CV_64F), cam.K, cam.raw.size(), CV_16SC2, map1, map2);
  cv::remap(cam.raw, want, map1, map2, cv::INTER_LINEAR);
  EXPECT_EQ(cv::norm(cv_bridge::toCvShare(got_image, "bgr8")->image, want, cv::NORM_INF), 0);
}

// A result of the image library through the runtime as a ROS message: ChessboardCorners' corners,
// sent by ResultPublisher as apex/ChessboardCorners, equal to OpenCV's own.
TEST(Camera, ResultPublisherSendsTheBoardsCornersAsAMessage) {
  const LeftCamera cam = leftCamera(ros::Time(1700000001, 5));
  ros::NodeHandle nh;
  std::mutex m;
  std::condition_variable arrived;
  apex::ChessboardCorners::ConstPtr got;
  auto sub = nh.subscribe<apex::ChessboardCorners>("/camera/board", 1, [&](const apex::ChessboardCorners::ConstPtr& c) {
    std::lock_guard<std::mutex> l(m);
    if (c->header.stamp == cam.info.header.stamp) got = c;
    arrived.notify_all();
  });
  sendUntil(cam, m, arrived, [&] { return got != nullptr; });
  std::lock_guard<std::mutex> l(m);
  ASSERT_TRUE(got) << "nothing on /camera/board";
  EXPECT_EQ(got->header.frame_id, "left_camera");
  EXPECT_EQ(got->width, static_cast<std::uint32_t>(cam.raw.cols));
  EXPECT_EQ(got->pattern_width, 9u);
  EXPECT_EQ(got->pattern_height, 6u);
  ASSERT_TRUE(got->found);
  std::vector<cv::Point2f> want;  // as ChessboardCorners finds them, with its defaults
  ASSERT_TRUE(
      cv::findChessboardCorners(cam.raw, cv::Size(9, 6), want, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE));
  cv::Mat gray;
  cv::cvtColor(cam.raw, gray, cv::COLOR_BGR2GRAY);
  cv::cornerSubPix(gray, want, cv::Size(11, 11), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.001));
  ASSERT_EQ(got->corners.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(got->corners[i].x, want[i].x) << i;
    EXPECT_EQ(got->corners[i].y, want[i].y) << i;
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_sensors");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
