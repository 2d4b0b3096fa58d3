// Depth nodes on generated depth images (a ramp with missing pixels) against depth_image_proc's
// computation written out here point by point, and the way back: a cloud projected into the camera.
#include <gmock/gmock.h>

#include <cmath>
#include <limits>

#include "apex_nodes/cloud.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using apex_nodes::Cloud;
using apex_nodes::Image;
using ::testing::HasSubstr;
using CameraInfo = sensor_msgs::CameraInfo;

namespace {

constexpr int kW = 64, kH = 48;
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
// The model's P (what depth_image_proc takes, through image_geometry) differs from its K, as after
// rectification: the nodes must use P. Dyadic values, so that ROI and binning arithmetic is exact.
constexpr double kFx = 52.5, kFy = 51.75, kCx = 31.625, kCy = 23.375;

std_msgs::Header cameraHeader() {
  std_msgs::Header h;
  h.frame_id = "camera";
  h.stamp = ros::Time(7, 250000000);
  return h;
}

std::shared_ptr<CameraInfo> camera() {
  auto c = std::make_shared<CameraInfo>();
  c->header = cameraHeader();
  c->width = kW, c->height = kH;
  c->distortion_model = "plumb_bob";
  c->D = {0, 0, 0, 0, 0};
  c->K = {50, 0, 32, 0, 50, 24, 0, 0, 1};
  c->R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  c->P = {kFx, 0, kCx, 0, 0, kFy, kCy, 0, 0, 0, 1, 0};
  return c;
}

std::shared_ptr<Image> image(cv::Mat mat, const std::string& encoding) {
  auto i = std::make_shared<Image>();
  i->header = cameraHeader();
  i->encoding = encoding;
  i->mat = std::move(mat);
  return i;
}

/** Millimetres: a ramp 500..3400, 0 (missing) where (u + v) % 7 == 0. */
cv::Mat millimetres() {
  cv::Mat m(kH, kW, CV_16UC1);
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u) m.at<std::uint16_t>(v, u) = (u + v) % 7 ? std::uint16_t(500 + 37 * u + 11 * v) : 0;
  return m;
}

/** Metres: a ramp 0.5..2.3 with NaN, 0 and infinity (all missing) scattered over it. */
cv::Mat metres() {
  cv::Mat m(kH, kW, CV_32FC1);
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u)
      m.at<float>(v, u) = (u + 2 * v) % 9 == 0    ? kNan
                          : (3 * u + v) % 13 == 0 ? 0.f
                          : u == 5 && v == 7      ? std::numeric_limits<float>::infinity()
                                                  : 0.5f + 0.013f * u + 0.021f * v;
  return m;
}

/** The depth in metres at (u, v), NaN where missing. */
float depthAt(const cv::Mat& m, int u, int v) {
  if (m.type() == CV_16UC1) {
    const std::uint16_t d = m.at<std::uint16_t>(v, u);
    return d ? d * 0.001f : kNan;
  }
  const float d = m.at<float>(v, u);
  return std::isfinite(d) && d != 0 ? d : kNan;
}

/** depth_image_proc's convert<T>() (depth_conversions.h) at one pixel: cx as a float, the unit
 *  (0.001 for millimetres, 1 for metres) and 1/fx folded into one float constant, then
 *  (u - cx) * raw_depth * constant. The textbook x = (u - cx) * d / fx is the same number up to
 *  float rounding only (other operations, in another order), so the nodes are compared exactly with
 *  this expression and within a relative 1e-6 with the textbook one. */
pcl::PointXYZ depthImageProc(const cv::Mat& m, int u, int v) {
  const bool mm = m.type() == CV_16UC1;
  const double unit_scaling = mm ? double(0.001f) : 1.0;
  const float center_x = float(kCx), center_y = float(kCy);
  const float constant_x = float(unit_scaling / kFx), constant_y = float(unit_scaling / kFy);
  if (std::isnan(depthAt(m, u, v))) return pcl::PointXYZ(kNan, kNan, kNan);
  const float raw = mm ? float(m.at<std::uint16_t>(v, u)) : m.at<float>(v, u);
  return pcl::PointXYZ((u - center_x) * raw * constant_x, (v - center_y) * raw * constant_y, depthAt(m, u, v));
}

const Cloud& cloudOf(const Message& m) {
  auto c = m.as<Cloud>();
  if (!c) throw std::runtime_error("expected a cloud, got " + m.typeName());
  EXPECT_EQ(c->header, cameraHeader());
  EXPECT_EQ(c->points->width, std::uint32_t(kW));
  EXPECT_EQ(c->points->height, std::uint32_t(kH));
  EXPECT_FALSE(c->points->is_dense);
  return *c;
}

/** Every pixel's point against depth_image_proc's, exactly, and against the textbook formula. */
template <class Point>
void expectDepthImageProc(const pcl::PointCloud<Point>& got, const cv::Mat& depth) {
  int valid = 0;
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u) {
      const Point& p = got.at(u, v);
      const pcl::PointXYZ want = depthImageProc(depth, u, v);
      if (std::isnan(want.z)) {
        ASSERT_TRUE(std::isnan(p.x) && std::isnan(p.y) && std::isnan(p.z)) << u << ", " << v;
        continue;
      }
      ++valid;
      ASSERT_EQ(p.x, want.x) << u << ", " << v;
      ASSERT_EQ(p.y, want.y) << u << ", " << v;
      ASSERT_EQ(p.z, want.z) << u << ", " << v;
      const double d = depthAt(depth, u, v), x = (u - kCx) * d / kFx, y = (v - kCy) * d / kFy;
      ASSERT_NEAR(p.x, x, 1e-6 * std::abs(x) + 1e-7) << u << ", " << v;
      ASSERT_NEAR(p.y, y, 1e-6 * std::abs(y) + 1e-7) << u << ", " << v;
    }
  EXPECT_GT(valid, kW * kH * 3 / 4);
  EXPECT_LT(valid, kW * kH);
}

Message share(std::shared_ptr<const Image> i) { return Message::share<Image>(std::move(i)); }
Message share(std::shared_ptr<const CameraInfo> c) { return Message::share<CameraInfo>(std::move(c)); }
Message share(std::shared_ptr<const Cloud> c) { return Message::share<Cloud>(std::move(c)); }

pcl::PointCloud<pcl::PointXYZ> depthToCloud(NodeHarness& h, std::shared_ptr<const Image> depth,
                                            std::shared_ptr<const CameraInfo> info = camera()) {
  const Cloud& c = cloudOf(h.run({share(std::move(depth)), share(std::move(info))}));
  EXPECT_EQ(apex_nodes::fieldNames(*c.points), "x, y, z");
  return apex_nodes::typedPoints<pcl::PointXYZ>(c);
}

TEST(DepthNodes, DepthToCloudMillimetresIsDepthImageProcs) {
  NodeHarness h("apex_nodes/DepthToCloud", {"depth", "camera_info"}, "cloud");
  expectDepthImageProc(depthToCloud(h, image(millimetres(), "16UC1")), millimetres());
  expectDepthImageProc(depthToCloud(h, image(millimetres(), "mono16")), millimetres());  // the same: millimetres
}

TEST(DepthNodes, DepthToCloudMetresIsDepthImageProcs) {
  NodeHarness h("apex_nodes/DepthToCloud", {"depth", "camera_info"}, "cloud");
  const auto points = depthToCloud(h, image(metres(), "32FC1"));
  expectDepthImageProc(points, metres());
  EXPECT_TRUE(std::isnan(points.at(5, 7).z));  // infinity
  EXPECT_TRUE(std::isnan(points.at(0, 0).z));  // NaN
  EXPECT_TRUE(std::isnan(points.at(13, 0).z));  // 0
}

TEST(DepthNodes, DepthToCloudAppliesRoiAndBinningAsImageGeometry) {
  // The full sensor 160x120; the image: the ROI 128x96 at (10, 6), binned 2x2 to 64x48. image_geometry
  // moves the principal point by the offset, then scales by 1/binning: the same intrinsics as camera().
  auto full = camera();
  full->width = 160, full->height = 120, full->binning_x = 2, full->binning_y = 2;
  full->roi.x_offset = 10, full->roi.y_offset = 6, full->roi.width = 128, full->roi.height = 96;
  full->P = {2 * kFx, 0, 2 * kCx + 10, 0, 0, 2 * kFy, 2 * kCy + 6, 0, 0, 0, 1, 0};
  NodeHarness h("apex_nodes/DepthToCloud", {"depth", "camera_info"}, "cloud");
  expectDepthImageProc(depthToCloud(h, image(millimetres(), "16UC1"), full), millimetres());
}

TEST(DepthNodes, DepthToCloudErrorsNameTheProblem) {
  NodeHarness h("apex_nodes/DepthToCloud", {"depth", "camera_info"}, "cloud");
  auto run = [&](std::shared_ptr<const Image> depth, std::shared_ptr<const CameraInfo> info) {
    EXPECT_TRUE(h.run({share(std::move(depth)), share(std::move(info))}).isNothing());
    return h.error();
  };
  cv::Mat bgr(kH, kW, CV_8UC3, cv::Scalar::all(1));
  EXPECT_THAT(run(image(bgr, "bgr8"), camera()),
              HasSubstr("depth image encoding 'bgr8' is not 16UC1, mono16 (millimetres) or 32FC1 (metres)"));
  EXPECT_THAT(run(image(cv::Mat(24, 32, CV_16UC1, cv::Scalar(1000)), "16UC1"), camera()),
              HasSubstr("camera model 64x48 on frame 'camera' is for images of 64x48, the depth image is 32x24"));
  auto uncalibrated = camera();
  uncalibrated->K.fill(0);
  EXPECT_THAT(run(image(millimetres(), "16UC1"), uncalibrated),
              HasSubstr("camera model 64x48 on frame 'camera' is not calibrated: K is all zero"));
  auto elsewhere = image(millimetres(), "16UC1");
  elsewhere->header.frame_id = "other_camera";
  EXPECT_THAT(run(elsewhere, camera()),
              HasSubstr("camera model 64x48 on frame 'camera' is not for the depth image on frame 'other_camera'"));
  elsewhere->header.frame_id.clear();  // no frame: nothing to disagree with
  EXPECT_FALSE(h.run({share(std::shared_ptr<const Image>(elsewhere)), share(camera())}).isNothing());
}

/** bgr8: blue 4u, green 5v, red 2(u + v). */
cv::Mat colours() {
  cv::Mat m(kH, kW, CV_8UC3);
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u)
      m.at<cv::Vec3b>(v, u) = cv::Vec3b(std::uint8_t(4 * u), std::uint8_t(5 * v), std::uint8_t(2 * (u + v)));
  return m;
}

TEST(DepthNodes, DepthColorToCloudColoursEveryPixel) {
  NodeHarness h("apex_nodes/DepthColorToCloud", {"depth", "color", "camera_info"}, "cloud");
  cv::Mat rgb;
  cv::Mat channels[3];
  cv::split(colours(), channels);
  std::swap(channels[0], channels[2]);
  cv::merge(channels, 3, rgb);
  for (const auto& [mat, encoding] : {std::pair{colours(), "bgr8"}, std::pair{rgb, "rgb8"}}) {
    const Cloud& c = cloudOf(h.run({share(image(metres(), "32FC1")), share(image(mat, encoding)), share(camera())}));
    EXPECT_EQ(apex_nodes::fieldNames(*c.points), "x, y, z, rgb");
    const auto points = apex_nodes::typedPoints<pcl::PointXYZRGB>(c);
    expectDepthImageProc(points, metres());
    for (int v = 0; v < kH; ++v)
      for (int u = 0; u < kW; ++u) {  // with depth or without, as depth_image_proc
        const pcl::PointXYZRGB& p = points.at(u, v);
        ASSERT_EQ(int(p.b), (4 * u) % 256) << encoding << " " << u << ", " << v;
        ASSERT_EQ(int(p.g), (5 * v) % 256) << encoding << " " << u << ", " << v;
        ASSERT_EQ(int(p.r), (2 * (u + v)) % 256) << encoding << " " << u << ", " << v;
        ASSERT_EQ(int(p.a), 255);
      }
  }
  EXPECT_TRUE(
      h.run({share(image(metres(), "32FC1")), share(image(colours()(cv::Rect(0, 0, 32, 24)).clone(), "bgr8")), share(camera())})
          .isNothing());
  EXPECT_THAT(h.error(), HasSubstr("the colour image is 32x24, the depth image 64x48"));
  EXPECT_TRUE(h.run({share(image(metres(), "32FC1")), share(image(metres(), "32FC1")), share(camera())}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("colour image encoding '32FC1' (1 channels) is not bgr8, rgb8"));
}

/** DepthToCloud's cloud of `depth`, projected back by CloudToDepth. */
cv::Mat roundTrip(const std::shared_ptr<const Image>& depth) {
  NodeHarness to("apex_nodes/DepthToCloud", {"depth", "camera_info"}, "cloud");
  NodeHarness back("apex_nodes/CloudToDepth", {"cloud", "camera_info"}, "depth");
  const Message cloud = to.run({share(depth), share(camera())});
  auto out = back.run({cloud, share(camera())}).as<Image>();
  if (!out) throw std::runtime_error("CloudToDepth sent no image: " + back.error());
  EXPECT_EQ(out->header, cameraHeader());
  EXPECT_EQ(out->encoding, "32FC1");
  EXPECT_EQ(out->mat.type(), CV_32FC1);
  return out->mat;
}

TEST(DepthNodes, CloudToDepthRoundTripsDepthToCloud) {
  for (const cv::Mat& depth : {metres(), millimetres()}) {
    const cv::Mat got = roundTrip(image(depth, depth.type() == CV_16UC1 ? "16UC1" : "32FC1"));
    ASSERT_EQ(got.size(), cv::Size(kW, kH));
    for (int v = 0; v < kH; ++v)
      for (int u = 0; u < kW; ++u) {
        const float want = depthAt(depth, u, v);
        if (std::isnan(want)) ASSERT_TRUE(std::isnan(got.at<float>(v, u))) << u << ", " << v;
        else ASSERT_NEAR(got.at<float>(v, u), want, 1e-5) << u << ", " << v;
      }
  }
}

TEST(DepthNodes, CloudToDepthKeepsTheNearestPointOnTheImage) {
  NodeHarness h("apex_nodes/CloudToDepth", {"cloud", "camera_info"}, "depth");
  pcl::PointCloud<pcl::PointXYZ> points;
  auto at = [](double u, double v, float z) {  // the point that projects to (u, v) at depth z
    return pcl::PointXYZ(float((u - kCx) * z / kFx), float((v - kCy) * z / kFy), z);
  };
  points.push_back(at(10, 20, 2.f));
  points.push_back(at(10.3, 19.8, 1.5f));  // the same pixel, nearer
  points.push_back(at(10, 20, 3.f));  // the same pixel, farther
  points.push_back(at(40, 5, 1.f));
  points.push_back(pcl::PointXYZ(0.1f, 0.1f, -1.f));  // behind the camera
  points.push_back(at(-3, 5, 1.f));  // off the image
  points.push_back(at(kW + 2, 5, 1.f));
  points.push_back(pcl::PointXYZ(kNan, 0, 1));
  const auto out = h.run({share(apex_nodes::makeCloud(cameraHeader(), points)), share(camera())}).as<Image>();
  ASSERT_TRUE(out);
  ASSERT_EQ(out->mat.size(), cv::Size(kW, kH));
  EXPECT_EQ(out->mat.at<float>(20, 10), 1.5f);
  EXPECT_EQ(out->mat.at<float>(5, 40), 1.f);
  EXPECT_EQ(cv::countNonZero(out->mat == out->mat), 2);  // NaN elsewhere (NaN != NaN)

  auto lidar = cameraHeader();
  lidar.frame_id = "lidar";
  EXPECT_TRUE(h.run({share(apex_nodes::makeCloud(lidar, points)), share(camera())}).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("camera model 64x48 on frame 'camera' is not for the cloud on frame 'lidar'"));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
