// Image nodes against the same OpenCV call made directly (pixel-exact), and
// their behaviour on input they cannot handle.
#include <gmock/gmock.h>

#include <unistd.h>

#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cv_bridge/cv_bridge.h>

#include "apex_nodes/ros_convert.hpp"
#include "apex_nodes/types.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;
using apex_nodes::Image;
using apex_nodes::Regions;
using ::testing::HasSubstr;

namespace {

/** A deterministic textured BGR test image. */
cv::Mat scene() {
  cv::Mat m(120, 160, CV_8UC3);
  cv::RNG rng(1);
  rng.fill(m, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(m, m, cv::Size(9, 9), 0);
  cv::rectangle(m, cv::Rect(20, 30, 40, 30), cv::Scalar::all(10), cv::FILLED);
  cv::circle(m, cv::Point(110, 70), 20, cv::Scalar::all(240), cv::FILLED);
  return m;
}

cv::Mat gray() {
  cv::Mat g;
  cv::cvtColor(scene(), g, cv::COLOR_BGR2GRAY);
  return g;
}

/** The image a node sent, with its header checked against the input's. */
const Image& out(const Message& m) {
  auto i = m.as<Image>();
  if (!i) throw std::runtime_error("expected an image, got " + m.typeName());
  expectCameraHeader(i->header);
  return *i;
}

TEST(ImageNodes, AdaptiveThresholdMatchesOpenCV) {
  NodeHarness h("apex_nodes/AdaptiveThreshold", {"image"}, "image");
  h.set("method", "gaussian");
  h.set("threshold_type", "binary_inv");
  h.set("block_size", "15");
  h.set("c", "4");
  cv::Mat want;
  cv::adaptiveThreshold(gray(), want, 255, cv::ADAPTIVE_THRESH_GAUSSIAN_C, cv::THRESH_BINARY_INV, 15, 4);
  const Image& got = out(h.run(imageOf(gray(), "mono8")));
  expectSameMat(got.mat, want);
  EXPECT_EQ(got.encoding, "mono8");
  auto st = h.graph().setParameter("node", "block_size", "10");  // even: refused, as in the paper's Fig. 3
  EXPECT_THAT(st.message(), HasSubstr("not on the step"));
}

TEST(ImageNodes, AdaptiveThresholdRefusesColourImages) {
  NodeHarness h("apex_nodes/AdaptiveThreshold", {"image"}, "image");
  EXPECT_TRUE(h.run(imageOf(scene(), "bgr8")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("cannot handle 3-channel images (encoding 'bgr8')"));
  EXPECT_FALSE(h.run(imageOf(gray(), "mono8")).isNothing());  // keeps running, error cleared
  EXPECT_EQ(h.error(), "");
}

TEST(ImageNodes, RotateExactAndAnyAngle) {
  NodeHarness h("apex_nodes/Rotate", {"image"}, "image");
  cv::Mat want;
  cv::rotate(scene(), want, cv::ROTATE_90_COUNTERCLOCKWISE);
  expectSameMat(out(h.run(imageOf(scene(), "bgr8"))).mat, want);  // default: 90 degrees
  h.set("angle", "-1.5707963267948966");
  cv::rotate(scene(), want, cv::ROTATE_90_CLOCKWISE);
  expectSameMat(out(h.run(imageOf(scene(), "bgr8"))).mat, want);
  h.set("angle", "0.5");
  const cv::Mat m = cv::getRotationMatrix2D(cv::Point2f(80, 60), 0.5 * 180 / M_PI, 1.0);
  cv::warpAffine(scene(), want, m, scene().size());
  expectSameMat(out(h.run(imageOf(scene(), "bgr8"))).mat, want);
}

TEST(ImageNodes, ColorConvertMatchesOpenCVAndChecksChannels) {
  NodeHarness h("apex_nodes/ColorConvert", {"image"}, "image");
  const Image& g = out(h.run(imageOf(scene(), "bgr8")));
  expectSameMat(g.mat, gray());
  EXPECT_EQ(g.encoding, "mono8");
  h.set("conversion", "BGR2HSV");
  cv::Mat hsv;
  cv::cvtColor(scene(), hsv, cv::COLOR_BGR2HSV);
  expectSameMat(out(h.run(imageOf(scene(), "bgr8"))).mat, hsv);
  EXPECT_TRUE(h.run(imageOf(gray(), "mono8")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("BGR2HSV needs a 3-channel image, got 1 channels ('mono8')"));
  EXPECT_THAT(h.graph().setParameter("node", "conversion", "BGR2XYZ").message(), HasSubstr("not one of"));
}

/** `scene()` with the two pixels of each horizontal pair alike: what YUV 4:2:2, which gives a
 *  pair one U and one V, keeps but for rounding. */
cv::Mat pairedScene() {
  cv::Mat half, out;
  cv::resize(scene(), half, cv::Size(80, 120), 0, 0, cv::INTER_AREA);
  cv::resize(half, out, scene().size(), 0, 0, cv::INTER_NEAREST);
  return out;
}

/** `bgr` as a camera's YUV 4:2:2 frame in UYVY byte order (U Y0 V Y1 per pixel pair), by the
 *  BT.601 video-range formulas (Y in 16..235) that OpenCV's 4:2:2 conversions invert. */
cv::Mat toUyvy(const cv::Mat& bgr) {
  auto luma = [](const cv::Vec3d& p) { return cv::saturate_cast<uchar>(16 + 0.257 * p[2] + 0.504 * p[1] + 0.098 * p[0]); };
  cv::Mat out(bgr.size(), CV_8UC2);
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x + 1 < bgr.cols; x += 2) {
      const cv::Vec3d a = bgr.at<cv::Vec3b>(y, x), b = bgr.at<cv::Vec3b>(y, x + 1), m = (a + b) / 2;
      const uchar u = cv::saturate_cast<uchar>(128 - 0.148 * m[2] - 0.291 * m[1] + 0.439 * m[0]);
      const uchar v = cv::saturate_cast<uchar>(128 + 0.439 * m[2] - 0.368 * m[1] - 0.071 * m[0]);
      out.at<cv::Vec2b>(y, x) = {u, luma(a)};
      out.at<cv::Vec2b>(y, x + 1) = {v, luma(b)};
    }
  return out;
}

/** The same frame in YUYV byte order (Y0 U Y1 V): each pixel's two bytes swapped. */
cv::Mat toYuyv(const cv::Mat& uyvy) {
  std::vector<cv::Mat> bytes;
  cv::split(uyvy, bytes);
  cv::Mat out;
  cv::merge(std::vector<cv::Mat>{bytes[1], bytes[0]}, out);
  return out;
}

TEST(ImageNodes, ColorConvertReadsCameraYuv422AsRosSendsIt) {
  // A ROS "yuv422" message (UYVY) becomes a 2-channel image, and ColorConvert makes BGR or gray of it.
  const cv::Mat paired = pairedScene(), uyvy = toUyvy(paired);
  std_msgs::Header header;
  header.stamp = ros::Time(42, 7), header.frame_id = "camera";
  const auto frame = apex_nodes::fromRos(cv_bridge::CvImage(header, "yuv422", uyvy).toImageMsg());
  ASSERT_EQ(frame->mat.type(), CV_8UC2);
  ASSERT_EQ(frame->mat.size(), paired.size());
  NodeHarness h("apex_nodes/ColorConvert", {"image"}, "image");
  h.set("conversion", "UYVY2BGR");
  const Image& bgr = out(h.run(frame));
  EXPECT_EQ(bgr.encoding, "bgr8");
  cv::Mat want;
  cv::cvtColor(uyvy, want, cv::COLOR_YUV2BGR_UYVY);
  expectSameMat(bgr.mat, want);  // size and type too
  EXPECT_LE(cv::norm(bgr.mat, paired, cv::NORM_INF), 3.0);  // the colours sent, but for rounding
  h.set("conversion", "UYVY2GRAY");
  const Image& g = out(h.run(frame));
  EXPECT_EQ(g.encoding, "mono8");
  ASSERT_EQ(g.mat.type(), CV_8UC1);
  cv::Mat luma, video;
  cv::extractChannel(uyvy, luma, 1);
  expectSameMat(g.mat, luma);  // the gray image is Y as sent: video range
  cv::cvtColor(paired, video, cv::COLOR_BGR2GRAY);
  video.convertTo(video, CV_8U, 219 / 255.0, 16);
  EXPECT_LE(cv::norm(g.mat, video, cv::NORM_INF), 2.0);
  // YUYV ("yuv422_yuy2"): the same pixels from the other byte order.
  h.set("conversion", "YUYV2BGR");
  expectSameMat(out(h.run(imageOf(toYuyv(uyvy), "yuv422_yuy2"))).mat, bgr.mat);
  h.set("conversion", "YUYV2GRAY");
  expectSameMat(out(h.run(imageOf(toYuyv(uyvy), "yuv422_yuy2"))).mat, g.mat);
  // The wrong shape of input: errors naming it.
  h.set("conversion", "UYVY2BGR");
  EXPECT_TRUE(h.run(imageOf(scene(), "bgr8")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("UYVY2BGR needs a 2-channel image, got 3 channels ('bgr8')"));
  EXPECT_TRUE(h.run(imageOf(uyvy.colRange(0, 159).clone(), "yuv422")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("an even width, got 159"));
}

TEST(ImageNodes, MorphologyMatchesOpenCV) {
  NodeHarness h("apex_nodes/Morphology", {"image"}, "image");
  h.set("operation", "close");
  h.set("shape", "ellipse");
  h.set("kernel_size", "5");
  h.set("iterations", "2");
  cv::Mat want;
  cv::morphologyEx(gray(), want, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(5, 5)), cv::Point(-1, -1),
                   2);
  expectSameMat(out(h.run(imageOf(gray(), "mono8"))).mat, want);
}

TEST(ImageNodes, SmallFiltersMatchOpenCV) {
  cv::Mat want;
  {
    NodeHarness h("apex_nodes/GaussianBlur", {"image"}, "image");
    h.set("kernel_size", "7");
    h.set("sigma", "1.5");
    cv::GaussianBlur(scene(), want, cv::Size(7, 7), 1.5);
    expectSameMat(out(h.run(imageOf(scene(), "bgr8"))).mat, want);
  }
  {
    NodeHarness h("apex_nodes/Threshold", {"image"}, "image");
    h.set("otsu", "true");
    cv::threshold(gray(), want, 128, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    expectSameMat(out(h.run(imageOf(gray(), "mono8"))).mat, want);
  }
  {
    NodeHarness h("apex_nodes/Canny", {"image"}, "edges");
    cv::Canny(gray(), want, 50, 150);
    expectSameMat(out(h.run(imageOf(gray(), "mono8"))).mat, want);
  }
  {
    NodeHarness h("apex_nodes/Resize", {"image"}, "image");
    cv::resize(scene(), want, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
    expectSameMat(out(h.run(imageOf(scene(), "bgr8"))).mat, want);
  }
  {
    NodeHarness h("apex_nodes/Crop", {"image"}, "image");
    h.set("x", "150");
    h.set("y", "100");
    expectSameMat(out(h.run(imageOf(scene(), "bgr8"))).mat, scene()(cv::Rect(150, 100, 10, 20)));  // clipped
    h.set("x", "500");
    EXPECT_TRUE(h.run(imageOf(scene(), "bgr8")).isNothing());
    EXPECT_THAT(h.error(), HasSubstr("outside the 160x120 image"));
  }
}

TEST(ImageNodes, BlobDetectionFindsRegionsWithAreaFilter) {
  cv::Mat binary = cv::Mat::zeros(100, 200, CV_8UC1);
  cv::rectangle(binary, cv::Rect(10, 10, 20, 10), cv::Scalar(255), cv::FILLED);  // 200 px
  cv::rectangle(binary, cv::Rect(50, 40, 30, 30), cv::Scalar(255), cv::FILLED);  // 900 px
  cv::rectangle(binary, cv::Rect(150, 80, 2, 2), cv::Scalar(255), cv::FILLED);  // 4 px: noise
  NodeHarness h("apex_nodes/BlobDetection", {"image"}, "regions");
  h.set("min_area", "50");
  auto regions = h.run(imageOf(binary, "mono8")).as<Regions>();
  ASSERT_TRUE(regions);
  ASSERT_EQ(regions->regions.size(), 2u);
  EXPECT_EQ(regions->regions[0].box, cv::Rect(10, 10, 20, 10));
  EXPECT_EQ(regions->regions[0].area, 200);
  EXPECT_EQ(regions->regions[1].box, cv::Rect(50, 40, 30, 30));
  EXPECT_NEAR(regions->regions[1].centroid.x, 64.5, 1e-9);
  EXPECT_EQ(regions->header.stamp, ros::Time(42, 7));
}

TEST(ImageNodes, DrawRegionsDrawsTheBoxes) {
  NodeHarness h("apex_nodes/DrawRegions", {"image", "regions"}, "image");
  auto regions = std::make_shared<Regions>();
  apex_nodes::Region r;
  r.box = cv::Rect(5, 5, 30, 20);
  regions->regions.push_back(r);
  const Image& got = out(h.run({Message::share<Image>(imageOf(gray(), "mono8")), Message::share<Regions>(regions)}));
  cv::Mat want;
  cv::cvtColor(gray(), want, cv::COLOR_GRAY2BGR);
  cv::rectangle(want, r.box, cv::Scalar(0, 255, 0), 2);
  expectSameMat(got.mat, want);
  EXPECT_EQ(got.encoding, "bgr8");
}

TEST(ImageNodes, DrawRegionsWritesATrackersIdAsHashId) {
  NodeHarness h("apex_nodes/DrawRegions", {"image", "regions"}, "image");
  auto regions = std::make_shared<Regions>();
  apex_nodes::Region r;
  r.box = cv::Rect(40, 60, 30, 20);
  r.label = 7;  // MultiObjectTracker's id; no confidence
  regions->regions.push_back(r);
  const Image& got = out(h.run({Message::share<Image>(imageOf(gray(), "mono8")), Message::share<Regions>(regions)}));
  cv::Mat want;  // the box, then "#7" above it on black, as for a classifier's "7 93%"
  cv::cvtColor(gray(), want, cv::COLOR_GRAY2BGR);
  cv::rectangle(want, r.box, cv::Scalar(0, 255, 0), 2);
  int baseline = 0;
  const cv::Size size = cv::getTextSize("#7", cv::FONT_HERSHEY_SIMPLEX, 0.6, 2, &baseline);
  const cv::Point at(r.box.x, r.box.y - 6);
  cv::rectangle(want, cv::Rect(at.x, at.y - size.height - 2, size.width + 2, size.height + baseline + 2), cv::Scalar::all(0),
                cv::FILLED);
  cv::putText(want, "#7", at + cv::Point(1, 0), cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 255, 0), 2, cv::LINE_AA);
  expectSameMat(got.mat, want);
}

TEST(ImageNodes, ImageExportWritesFramesOrCrops) {
  char dir[] = "/tmp/apex_export_XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  NodeHarness h("apex_nodes/ImageExport", {"image"}, "path");
  h.set("directory", std::string("'") + dir + "'");
  const std::string path = *h.run(imageOf(scene(), "bgr8")).as<std::string>();
  EXPECT_EQ(path, std::string(dir) + "/frame_0.png");
  expectSameMat(cv::imread(path), scene());  // PNG: lossless
  h.set("directory", "/nonexistent/dir");
  EXPECT_TRUE(h.run(imageOf(scene(), "bgr8")).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("directory '/nonexistent/dir' does not exist"));

  // Another run (a new node, numbering from 0) finds frame_0.png there: left as it is
  NodeHarness again("apex_nodes/ImageExport", {"image"}, "path");
  again.set("directory", std::string("'") + dir + "'");
  const cv::Mat other(4, 4, CV_8UC3, cv::Scalar(1, 2, 3));
  EXPECT_TRUE(again.run(imageOf(other, "bgr8")).isNothing());
  EXPECT_THAT(again.error(), HasSubstr("'" + path +
                                       "' exists (not written by this node): left as it is; set "
                                       "'overwrite' to replace such files, or choose another prefix or directory"));
  expectSameMat(cv::imread(path), scene());
  again.set("overwrite", "true");
  EXPECT_EQ(*again.run(imageOf(other, "bgr8")).as<std::string>(), std::string(dir) + "/frame_1.png");
  NodeHarness replacing("apex_nodes/ImageExport", {"image"}, "path");
  replacing.set("directory", std::string("'") + dir + "'");
  replacing.set("overwrite", "true");
  EXPECT_EQ(*replacing.run(imageOf(other, "bgr8")).as<std::string>(), path);
  expectSameMat(cv::imread(path), other);
  for (const char* f : {"frame_0.png", "frame_1.png"}) std::remove((std::string(dir) + "/" + f).c_str());
  rmdir(dir);
}

TEST(ImageNodes, EmptyImagesAreAnErrorNotACrash) {
  for (const char* type : {"apex_nodes/Rotate", "apex_nodes/GaussianBlur", "apex_nodes/Morphology"}) {
    NodeHarness h(type, {"image"}, "image");
    EXPECT_TRUE(h.run(imageOf(cv::Mat(), "bgr8")).isNothing()) << type;
    EXPECT_THAT(h.error(), HasSubstr("received an empty image")) << type;
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
