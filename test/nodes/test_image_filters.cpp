// Image filters (smoothing.cpp, derivatives.cpp, intensity.cpp, warp.cpp) on opencv-doc's real
// images, against the same OpenCV call made directly (pixel-exact, encoding and header too), and
// their errors on input they cannot handle; and the filters whose settings change nothing sending
// the frame's own message.
#include <gmock/gmock.h>

#include <cmath>
#include <iomanip>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <vector>

#include "apex_nodes/output_buffer.hpp"
#include "apex_nodes/types.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;

namespace {

TEST(ImageFilters, MedianBlurMatchesOpenCVAndNeeds8BitForLargeApertures) {
  const cv::Mat src = readData("baboon.jpg");
  NodeHarness h("apex_nodes/MedianBlur", {"image"}, "image");
  h.set("ksize", "7");
  cv::Mat want, wide;
  cv::medianBlur(src, want, 7);
  expectImage(h, h.run(imageOf(src, "bgr8")), want, "bgr8");
  readGrayData("baboon.jpg").convertTo(wide, CV_16U, 257);
  expectNothing(h, h.run(imageOf(wide, "mono16")), "ksize 7 needs an 8-bit image, got 16U ('mono16')");
  h.set("ksize", "5");
  cv::medianBlur(wide, want, 5);
  expectImage(h, h.run(imageOf(wide, "mono16")), want, "mono16");
}

TEST(ImageFilters, BilateralFilterMatchesOpenCV) {
  const cv::Mat src = readData("fruits.jpg");
  NodeHarness h("apex_nodes/BilateralFilter", {"image"}, "image");
  h.set("d", "7");
  h.set("sigma_color", "40");
  h.set("sigma_space", "20");
  h.set("border_type", "replicate");
  cv::Mat want, bgra;
  cv::bilateralFilter(src, want, 7, 40, 20, cv::BORDER_REPLICATE);
  expectImage(h, h.run(imageOf(src, "bgr8")), want, "bgr8");
  cv::cvtColor(src, bgra, cv::COLOR_BGR2BGRA);
  expectNothing(h, h.run(imageOf(bgra, "bgra8")), "cannot handle 4-channel images (encoding 'bgra8'); needs 1 or 3 channels");
}

TEST(ImageFilters, BoxFilterMatchesOpenCVNormalizedOrNot) {
  const cv::Mat src = readGrayData("building.jpg");
  NodeHarness h("apex_nodes/BoxFilter", {"image"}, "image");
  h.set("ksize", "9");
  cv::Mat want;
  cv::boxFilter(src, want, -1, cv::Size(9, 9));
  expectImage(h, h.run(imageOf(src, "mono8")), want, "mono8");
  h.set("normalize", "false");
  h.set("border_type", "constant");
  cv::boxFilter(src, want, -1, cv::Size(9, 9), cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
  expectImage(h, h.run(imageOf(src, "mono8")), want, "mono8");
}

/** cv::meanStdDev's deviation of the ksize × ksize window around each pixel `step` apart, away from the border. */
template <class Check>
void eachWindow(const cv::Mat& src, int ksize, int step, Check check) {
  const int r = ksize / 2;
  for (int y = r; y + r < src.rows; y += step)
    for (int x = r; x + r < src.cols; x += step) {
      cv::Scalar mean, dev;
      cv::meanStdDev(src(cv::Rect(x - r, y - r, ksize, ksize)), mean, dev);
      check(y, x, dev[0]);
    }
}

TEST(ImageFilters, StdDevFilterIsEachWindowsDeviationAsMeanStdDevGivesIt) {
  const cv::Mat src = readGrayData("building.jpg");
  NodeHarness h("apex_nodes/StdDevFilter", {"image"}, "image");
  h.set("ksize", "7");
  cv::Mat floats;
  src.convertTo(floats, CV_32F);
  const auto f = h.run(imageOf(floats, "32FC1")).as<apex_nodes::Image>();
  ASSERT_TRUE(f) << h.error();
  EXPECT_EQ(f->encoding, "32FC1");
  int checked = 0;
  eachWindow(src, 7, 5, [&](int y, int x, double dev) {
    ASSERT_NEAR(f->mat.at<float>(y, x), dev, 1e-3 * (1 + dev)) << x << "," << y;
    ++checked;
  });
  EXPECT_GT(checked, 5000);
  h.set("ksize", "5");
  h.set("scale", "10");  // 8-bit: tenths of a grey level, rounded, at most 255
  const auto b = h.run(imageOf(src, "mono8")).as<apex_nodes::Image>();
  ASSERT_TRUE(b) << h.error();
  EXPECT_EQ(b->encoding, "mono8");
  eachWindow(src, 5, 5, [&](int y, int x, double dev) {
    ASSERT_NEAR(b->mat.at<uchar>(y, x), std::min(255.0, std::round(10 * dev)), 1.0) << x << "," << y;
  });
  expectNothing(h, h.run(readDataImage("building.jpg")),
                "cannot handle 3-channel images (encoding 'bgr8'); needs a single-channel image");
}

TEST(ImageFilters, SobelMatchesOpenCVWithTheEncodingOfItsDepth) {
  const cv::Mat src = readGrayData("sudoku.png"), colour = readData("sudoku.png");
  NodeHarness h("apex_nodes/Sobel", {"image"}, "image");  // dx 1, dy 0, ksize 3, ddepth 16S
  cv::Mat want, floats;
  cv::Sobel(src, want, CV_16S, 1, 0, 3);
  expectImage(h, h.run(imageOf(src, "mono8")), want, "16SC1");
  h.set("dy", "2");
  h.set("ksize", "5");
  h.set("scale", "0.5");
  h.set("delta", "10");
  h.set("ddepth", "32F");
  h.set("border_type", "replicate");
  cv::Sobel(colour, want, CV_32F, 1, 2, 5, 0.5, 10, cv::BORDER_REPLICATE);
  expectImage(h, h.run(imageOf(colour, "bgr8")), want, "32FC3");
  h.set("ddepth", "16S");
  src.convertTo(floats, CV_32F);
  expectNothing(h, h.run(imageOf(floats, "32FC1")),
                "ddepth 16S cannot hold the derivatives of a 32F image ('32FC1'); choose 32F, 64F or same");
  h.set("dx", "0");
  h.set("dy", "0");
  expectNothing(h, h.run(imageOf(src, "mono8")), "dx and dy are both 0");
}

TEST(ImageFilters, ScharrMatchesOpenCVAndTakesOneDerivative) {
  const cv::Mat src = readGrayData("sudoku.png");
  NodeHarness h("apex_nodes/Scharr", {"image"}, "image");
  h.set("dx", "0");
  h.set("dy", "1");
  h.set("ddepth", "64F");
  cv::Mat want;
  cv::Scharr(src, want, CV_64F, 0, 1);
  expectImage(h, h.run(imageOf(src, "mono8")), want, "64FC1");
  h.set("dx", "1");
  expectNothing(h, h.run(imageOf(src, "mono8")), "Scharr takes one first derivative: dx = 1 or dy = 1, not dx = 1, dy = 1");
}

TEST(ImageFilters, LaplacianMatchesOpenCV) {
  const cv::Mat src = readGrayData("building.jpg");
  NodeHarness h("apex_nodes/Laplacian", {"image"}, "image");  // ksize 1, ddepth 16S
  cv::Mat want;
  cv::Laplacian(src, want, CV_16S, 1);
  expectImage(h, h.run(imageOf(src, "mono8")), want, "16SC1");
  h.set("ksize", "5");
  h.set("ddepth", "same");
  cv::Laplacian(src, want, -1, 5);
  expectImage(h, h.run(imageOf(src, "mono8")), want, "mono8");
}

TEST(ImageFilters, EqualizeHistMatchesOpenCVOnGray8BitOnly) {
  const cv::Mat src = readGrayData("home.jpg");
  NodeHarness h("apex_nodes/EqualizeHist", {"image"}, "image");
  cv::Mat want, wide;
  cv::equalizeHist(src, want);
  expectImage(h, h.run(imageOf(src, "mono8")), want, "mono8");
  expectNothing(h, h.run(readDataImage("home.jpg")),
                "cannot handle 3-channel images (encoding 'bgr8'); needs a single-channel image");
  src.convertTo(wide, CV_16U, 257);
  expectNothing(h, h.run(imageOf(wide, "mono16")), "needs an 8-bit image ('mono16')");
}

TEST(ImageFilters, ClaheMatchesOpenCVOn8And16BitImages) {
  const cv::Mat src = readGrayData("home.jpg");
  NodeHarness h("apex_nodes/CLAHE", {"image"}, "image");
  h.set("clip_limit", "3");
  h.set("tile_grid_size", "4");
  const cv::Ptr<cv::CLAHE> clahe = cv::createCLAHE(3, cv::Size(4, 4));
  cv::Mat want, wide, floats;
  clahe->apply(src, want);
  expectImage(h, h.run(imageOf(src, "mono8")), want, "mono8");
  src.convertTo(wide, CV_16U, 257);
  clahe->apply(wide, want);
  expectImage(h, h.run(imageOf(wide, "mono16")), want, "mono16");
  src.convertTo(floats, CV_32F);
  expectNothing(h, h.run(imageOf(floats, "32FC1")), "needs an 8- or 16-bit image, got 32F ('32FC1')");
}

TEST(ImageFilters, NormalizeMatchesOpenCVToARangeOrANorm) {
  const cv::Mat colour = readData("messi5.jpg");
  cv::Mat floats, want;
  readGrayData("messi5.jpg").convertTo(floats, CV_32F, 1 / 255.0, 0.2);
  NodeHarness h("apex_nodes/Normalize", {"image"}, "image");  // minmax to [0, 255]
  h.set("dtype", "8U");
  cv::normalize(floats, want, 0, 255, cv::NORM_MINMAX, CV_8U);
  expectImage(h, h.run(imageOf(floats, "32FC1")), want, "mono8");
  h.set("norm_type", "l2");
  h.set("alpha", "1");
  h.set("dtype", "32F");
  cv::normalize(colour, want, 1, 255, cv::NORM_L2, CV_32F);
  expectImage(h, h.run(imageOf(colour, "bgr8")), want, "32FC3");
}

TEST(ImageFilters, ConvertScaleMatchesOpenCVAndKeepsTheColourOrder) {
  const cv::Mat colour = readData("fruits.jpg"), src = readGrayData("fruits.jpg");
  cv::Mat rgb, want, wide;
  cv::cvtColor(colour, rgb, cv::COLOR_BGR2RGB);
  NodeHarness h("apex_nodes/ConvertScale", {"image"}, "image");
  h.set("rtype", "16U");
  h.set("alpha", "256");
  colour.convertTo(want, CV_16U, 256);
  expectImage(h, h.run(imageOf(colour, "bgr8")), want, "bgr16");
  rgb.convertTo(want, CV_16U, 256);
  expectImage(h, h.run(imageOf(rgb, "rgb8")), want, "rgb16");
  h.set("rtype", "32F");
  h.set("alpha", "0.004");
  h.set("beta", "-0.5");
  src.convertTo(want, CV_32F, 0.004, -0.5);
  expectImage(h, h.run(imageOf(src, "mono8")), want, "32FC1");
  src.convertTo(wide, CV_16U, 257);
  h.set("rtype", "8U");
  h.set("alpha", "0.00390625");
  h.set("beta", "0");
  wide.convertTo(want, CV_8U, 0.00390625);
  expectImage(h, h.run(imageOf(wide, "mono16")), want, "mono8");
}

TEST(ImageFilters, FlipMatchesOpenCVForEachCode) {
  const cv::Mat src = readData("messi5.jpg");
  NodeHarness h("apex_nodes/Flip", {"image"}, "image");
  for (const auto& [name, code] : std::vector<std::pair<std::string, int>>{{"horizontal", 1}, {"vertical", 0}, {"both", -1}}) {
    h.set("flip_code", name);
    cv::Mat want;
    cv::flip(src, want, code);
    expectImage(h, h.run(imageOf(src, "bgr8")), want, "bgr8");
  }
}

TEST(ImageFilters, PyrDownAndPyrUpMatchOpenCV) {
  const cv::Mat src = readData("sudoku.png");  // 558x563: odd rows
  cv::Mat want;
  NodeHarness down("apex_nodes/PyrDown", {"image"}, "image");
  cv::pyrDown(src, want);
  EXPECT_EQ(want.size(), cv::Size(279, 282));
  expectImage(down, down.run(imageOf(src, "bgr8")), want, "bgr8");
  NodeHarness up("apex_nodes/PyrUp", {"image"}, "image");
  cv::pyrUp(readGrayData("smarties.png"), want);
  EXPECT_EQ(want.size(), cv::Size(826, 712));
  expectImage(up, up.run(imageOf(readGrayData("smarties.png"), "mono8")), want, "mono8");
}

TEST(ImageFilters, WarpPerspectiveMatchesOpenCVOnARealHomography) {
  // graf1.png to graf3.png: opencv-doc's homography between two views of the same wall
  const cv::Mat src = readData("graf1.png");
  cv::Mat H, want;
  cv::FileStorage(kOpenCvData + "/H1to3p.xml", cv::FileStorage::READ)["H13"] >> H;
  ASSERT_EQ(H.size(), cv::Size(3, 3));
  ASSERT_EQ(H.type(), CV_64F);
  std::ostringstream m;
  m << std::setprecision(17) << "[";
  for (int i = 0; i < 9; ++i) m << (i ? ", " : "") << H.at<double>(i / 3, i % 3);
  m << "]";
  NodeHarness h("apex_nodes/WarpPerspective", {"image"}, "image");
  h.set("m", m.str());
  cv::warpPerspective(src, want, H, src.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  expectImage(h, h.run(imageOf(src, "bgr8")), want, "bgr8");
  h.set("inverse_map", "true");
  h.set("width", "400");
  h.set("height", "300");
  h.set("interpolation", "nearest");
  h.set("border_mode", "replicate");
  cv::warpPerspective(src, want, H, cv::Size(400, 300), cv::INTER_NEAREST | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
  expectImage(h, h.run(imageOf(src, "bgr8")), want, "bgr8");
  h.set("m", "[1, 0, 0, 0, 1, 0]");
  expectNothing(h, h.run(imageOf(src, "bgr8")), "'m' takes nine numbers (the 3x3 matrix, row by row), not 6");
}

/** The image `h`'s node sent for `frame`. */
std::shared_ptr<const apex_nodes::Image> sent(NodeHarness& h, const std::shared_ptr<const apex_nodes::Image>& frame) {
  const auto got = h.run(frame).as<apex_nodes::Image>();
  EXPECT_TRUE(got) << "the node sent no image: " << h.error();
  return got;
}

TEST(ImageFilters, SettingsThatChangeNothingSendTheFrameItself) {
  const auto frame = readDataImage("fruits.jpg");
  NodeHarness rotate("apex_nodes/Rotate", {"image"}, "image");
  for (const char* angle : {"0", "6.28318530717958", "-6.28318530717958"}) {  // 0 and whole turns (to 1e-9)
    rotate.set("angle", angle);
    EXPECT_EQ(sent(rotate, frame), frame) << angle;
  }
  rotate.set("angle", "3.141592653589793");
  EXPECT_NE(sent(rotate, frame), frame);
  NodeHarness resize("apex_nodes/Resize", {"image"}, "image");
  resize.set("scale", "1");
  EXPECT_EQ(sent(resize, frame), frame);
  NodeHarness scale("apex_nodes/ConvertScale", {"image"}, "image");  // alpha 1, beta 0, 8U
  EXPECT_EQ(sent(scale, frame), frame);
  scale.set("rtype", "same");
  EXPECT_EQ(sent(scale, frame), frame);
  scale.set("beta", "1");
  EXPECT_NE(sent(scale, frame), frame);

  NodeHarness warp("apex_nodes/WarpPerspective", {"image"}, "image");  // m: the identity
  cv::Mat want;
  cv::warpPerspective(frame->mat, want, cv::Matx33d::eye(), frame->mat.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  expectSameMat(want, frame->mat);  // what passing the frame on takes for granted
  EXPECT_EQ(sent(warp, frame), frame);
  warp.set("width", std::to_string(frame->mat.cols));
  EXPECT_EQ(sent(warp, frame), frame);
  warp.set("width", "100");
  EXPECT_NE(sent(warp, frame), frame);
  warp.set("width", "0");
  cv::Mat depth(64, 64, CV_32FC1, cv::Scalar(2.0f));
  depth.at<float>(10, 10) = NAN;  // the zero weights may spread it (0 * NaN): warped, as OpenCV warps it
  cv::warpPerspective(depth, want, cv::Matx33d::eye(), depth.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  const auto got = sent(warp, imageOf(depth, "32FC1"));
  ASSERT_TRUE(got);
  EXPECT_NE(got->mat.data, depth.data);
  cv::Mat got_values = got->mat.clone();
  cv::patchNaNs(got_values, -1), cv::patchNaNs(want, -1);  // NaN is not equal to itself
  expectSameMat(got_values, want);

  const auto gray = imageOf(readGrayData("fruits.jpg"), "mono8");
  NodeHarness split("apex_nodes/SplitChannels", {"image"}, "channel_0");
  EXPECT_EQ(sent(split, gray), gray);  // a single channel: the image itself
}

TEST(ImageFilters, AnOutputStillHeldDownstreamIsNotReusedButTheOneBeforeIsAgain) {
  // As in a pipeline of two thread groups: frame i is still downstream while the node makes
  // i + 1; when i is let go, i + 2 reuses its pixels (one output kept: a new image every frame).
  apex_nodes::Reused<apex_nodes::Image> outputs;
  auto a = outputs.next();
  a->mat.create(480, 640, CV_8UC3);
  const uchar* pixels_a = a->mat.data;
  std::shared_ptr<const apex_nodes::Image> frame_i = std::move(a);
  auto b = outputs.next();
  EXPECT_NE(b.get(), frame_i.get());  // never written while a receiver holds it
  std::shared_ptr<const apex_nodes::Image> frame_i1 = std::move(b);
  frame_i.reset();
  auto c = outputs.next();
  EXPECT_EQ(c->mat.data, pixels_a);
  EXPECT_NE(c.get(), frame_i1.get());
  std::vector<std::shared_ptr<const apex_nodes::Image>> held{frame_i1, c};
  for (int k = 0; k < 5; ++k) {  // all held: new ones, none of them handed out twice
    held.push_back(outputs.next());
    for (std::size_t j = 0; j + 1 < held.size(); ++j) EXPECT_NE(held.back(), held[j]);
  }
}

TEST(ImageFilters, DistanceTransformMatchesOpenCVAndSends32F) {
  cv::Mat binary, want;
  cv::threshold(readGrayData("sudoku.png"), binary, 128, 255, cv::THRESH_BINARY);
  NodeHarness h("apex_nodes/DistanceTransform", {"image"}, "image");  // l2, mask 3
  cv::distanceTransform(binary, want, cv::DIST_L2, cv::DIST_MASK_3, CV_32F);
  expectImage(h, h.run(imageOf(binary, "mono8")), want, "32FC1");
  h.set("mask_size", "precise");
  cv::distanceTransform(binary, want, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  expectImage(h, h.run(imageOf(binary, "mono8")), want, "32FC1");
  h.set("distance_type", "l1");
  h.set("mask_size", "5");
  cv::distanceTransform(binary, want, cv::DIST_L1, cv::DIST_MASK_5, CV_32F);
  expectImage(h, h.run(imageOf(binary, "mono8")), want, "32FC1");
  expectNothing(h, h.run(readDataImage("sudoku.png")),
                "cannot handle 3-channel images (encoding 'bgr8'); needs a single-channel image");
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
