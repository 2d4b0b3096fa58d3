// Camera models with images, on real data: opencv-doc's chessboard sequence (left01.jpg ...) and
// its calibration (left_intrinsics.yml, OpenCV's format). Rectify against OpenCV's own maps and
// remap on the same model; CameraInfoFile against camera_calibration_parsers' own writer.
#include <camera_calibration_parsers/parse.h>
#include <gmock/gmock.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "apex_nodes/types.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;
using apex_nodes::Image;
using sensor_msgs::CameraInfo;
using ::testing::HasSubstr;

namespace {

/** A frame of opencv-doc's chessboard sequence, bgr8, from the left camera. */
std::shared_ptr<const Image> chessboard(const std::string& name = "left01.jpg") { return readDataImage(name, "left_camera"); }

/** CameraInfoFile's model for the image, from `file`. */
Message modelFrom(const std::string& file, const std::shared_ptr<const Image>& image) {
  NodeHarness h("apex_nodes/CameraInfoFile", {"image"}, "camera_info");
  h.set("file", file);
  return h.run(image);
}

TEST(CameraNodes, RectifyEqualsOpenCvsRemapOnARealCalibration) {
  const auto image = chessboard();
  const Message info = modelFrom(kOpenCvData + "/left_intrinsics.yml", image);
  ASSERT_TRUE(info.as<CameraInfo>());
  EXPECT_EQ(info.as<CameraInfo>()->header, image->header);  // stamped like the frame it goes with

  NodeHarness h("apex_nodes/Rectify", {"image", "camera_info"}, "image");
  const Message out = h.run({Message::share<Image>(image), info});
  ASSERT_TRUE(out.as<Image>()) << h.error();
  const Image& got = *out.as<Image>();

  cv::FileStorage fs(kOpenCvData + "/left_intrinsics.yml", cv::FileStorage::READ);
  cv::Mat K, D, map1, map2, want;
  fs["camera_matrix"] >> K;
  fs["distortion_coefficients"] >> D;
  cv::initUndistortRectifyMap(K, D, cv::Mat::eye(3, 3, CV_64F), K, image->mat.size(), CV_16SC2, map1, map2);
  cv::remap(image->mat, want, map1, map2, cv::INTER_LINEAR);
  ASSERT_EQ(got.mat.size(), want.size());
  EXPECT_EQ(cv::norm(got.mat, want, cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(got.mat, image->mat, cv::NORM_L1) / image->mat.total(), 5.0);  // the lens's distortion was removed
  EXPECT_EQ(got.header, image->header);
  EXPECT_EQ(got.encoding, "bgr8");
}

TEST(CameraNodes, CameraInfoFileReadsRosCalibrationFiles) {
  CameraInfo written;
  written.width = 640, written.height = 480, written.distortion_model = "plumb_bob";
  written.K = {500, 0, 320, 0, 510, 240, 0, 0, 1};
  written.D = {-0.1, 0.01, 0, 0, 0};
  written.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  written.P = {500, 0, 320, 0, 0, 510, 240, 0, 0, 0, 1, 0};
  const std::string path = ::testing::TempDir() + "/apex_test_camera.yaml";
  ASSERT_TRUE(camera_calibration_parsers::writeCalibration(path, "left", written));
  const Message m = modelFrom(path, chessboard());
  ASSERT_TRUE(m.as<CameraInfo>());
  EXPECT_EQ(m.as<CameraInfo>()->K, written.K);
  EXPECT_EQ(m.as<CameraInfo>()->D, written.D);
  EXPECT_EQ(m.as<CameraInfo>()->P, written.P);
}

TEST(CameraNodes, AModelThatDoesNotFitTheImageIsAnErrorNamingBoth) {
  NodeHarness file("apex_nodes/CameraInfoFile", {"image"}, "camera_info");
  file.set("file", kOpenCvData + "/no_such_calibration.yml");
  EXPECT_TRUE(file.run(chessboard()).isNothing());
  EXPECT_THAT(file.error(), HasSubstr("cannot read the calibration file '" + kOpenCvData + "/no_such_calibration.yml'"));
  file.set("file", kOpenCvData + "/left01.jpg");
  EXPECT_TRUE(file.run(chessboard()).isNothing());
  EXPECT_THAT(file.error(), HasSubstr("is neither a ROS camera calibration"));

  const Message info = modelFrom(kOpenCvData + "/left_intrinsics.yml", chessboard());
  auto small = std::make_shared<Image>(*chessboard());
  cv::resize(small->mat, small->mat, cv::Size(320, 240));
  NodeHarness rectify("apex_nodes/Rectify", {"image", "camera_info"}, "image");
  EXPECT_TRUE(rectify.run({Message::share<Image>(small), info}).isNothing());
  EXPECT_THAT(rectify.error(), HasSubstr("camera model 640x480 on frame 'left_camera' is not for an image of 320x240"));
  EXPECT_TRUE(rectify.run({Message::share<Image>(chessboard()), Message::make(CameraInfo())}).isNothing());
  EXPECT_THAT(rectify.error(), HasSubstr("is not calibrated: K is all zero"));
}

TEST(CameraNodes, UndistortRegionsMovesCentroidsAsOpenCvDoes) {
  const auto image = chessboard();
  const Message info = modelFrom(kOpenCvData + "/left_intrinsics.yml", image);
  auto regions = std::make_shared<apex_nodes::Regions>();
  regions->header = image->header;
  apex_nodes::Region corner;  // near the image's corner, where the lens bends most
  corner.box = cv::Rect(10, 10, 40, 30), corner.centroid = cv::Point2d(30, 25);
  regions->regions = {corner};
  NodeHarness h("apex_nodes/UndistortRegions", {"regions", "camera_info"}, "regions");
  const Message out = h.run({Message::share<apex_nodes::Regions>(regions), info});
  ASSERT_TRUE(out.as<apex_nodes::Regions>()) << h.error();
  const auto& got = out.as<apex_nodes::Regions>()->regions.at(0);
  const CameraInfo& c = *info.as<CameraInfo>();
  std::vector<cv::Point2d> want;
  cv::undistortPoints(std::vector<cv::Point2d>{corner.centroid}, want, cv::Matx33d(c.K.data()), cv::Mat(c.D),
                      cv::Matx33d(c.R.data()), cv::Matx34d(c.P.data()));
  EXPECT_NEAR(got.centroid.x, want[0].x, 1e-9);
  EXPECT_NEAR(got.centroid.y, want[0].y, 1e-9);
  EXPECT_GT(cv::norm(got.centroid - corner.centroid), 5.0);  // the distortion near the corner is pixels, not noise
  EXPECT_TRUE(got.box.contains(cv::Point(int(got.centroid.x), int(got.centroid.y))));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
