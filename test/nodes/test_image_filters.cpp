// Image filters (smoothing.cpp, derivatives.cpp, intensity.cpp, warp.cpp) on opencv-doc's real
// images, against the same OpenCV call made directly (pixel-exact, encoding and header too), and
// their errors on input they cannot handle.
#include <gmock/gmock.h>

#include <iomanip>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "apex_nodes/types.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using apex_nodes::Image;
using ::testing::HasSubstr;

namespace {

const std::string kData = "/usr/share/doc/opencv-doc/examples/data";  // scripts/install_deps installs opencv-doc

cv::Mat load(const std::string& name, int flags = cv::IMREAD_COLOR) {
  cv::Mat m = cv::imread(kData + "/" + name, flags);
  if (m.empty()) ADD_FAILURE() << "cannot read " << kData << "/" << name << ": is opencv-doc installed?";
  return m;
}
cv::Mat gray(const std::string& name) { return load(name, cv::IMREAD_GRAYSCALE); }

std::shared_ptr<const Image> image(cv::Mat mat, const std::string& encoding) {
  auto i = std::make_shared<Image>();
  i->header.stamp = ros::Time(42, 7);
  i->header.frame_id = "camera";
  i->encoding = encoding;
  i->mat = std::move(mat);
  return i;
}

/** Runs the node on `in` and expects `want`, with `encoding` and the input's header. */
void expectResult(NodeHarness& h, const std::shared_ptr<const Image>& in, const cv::Mat& want, const std::string& encoding) {
  const Message m = h.run(in);
  ASSERT_TRUE(m.as<Image>()) << "the node sent no image: " << h.error();
  const Image& got = *m.as<Image>();
  EXPECT_EQ(got.header.stamp, ros::Time(42, 7));
  EXPECT_EQ(got.header.frame_id, "camera");
  EXPECT_EQ(got.encoding, encoding);
  ASSERT_EQ(got.mat.size(), want.size());
  ASSERT_EQ(got.mat.type(), want.type());
  EXPECT_EQ(cv::norm(got.mat, want, cv::NORM_INF), 0.0);
}

/** Runs the node on `in` and expects Nothing and an error saying `text`. */
void expectError(NodeHarness& h, const std::shared_ptr<const Image>& in, const std::string& text) {
  EXPECT_TRUE(h.run(in).isNothing());
  EXPECT_THAT(h.error(), HasSubstr(text));
}

TEST(ImageFilters, MedianBlurMatchesOpenCVAndNeeds8BitForLargeApertures) {
  const cv::Mat src = load("baboon.jpg");
  NodeHarness h("apex_nodes/MedianBlur", {"image"}, "image");
  h.set("ksize", "7");
  cv::Mat want, wide;
  cv::medianBlur(src, want, 7);
  expectResult(h, image(src, "bgr8"), want, "bgr8");
  gray("baboon.jpg").convertTo(wide, CV_16U, 257);
  expectError(h, image(wide, "mono16"), "ksize 7 needs an 8-bit image, got 16U ('mono16')");
  h.set("ksize", "5");
  cv::medianBlur(wide, want, 5);
  expectResult(h, image(wide, "mono16"), want, "mono16");
}

TEST(ImageFilters, BilateralFilterMatchesOpenCV) {
  const cv::Mat src = load("fruits.jpg");
  NodeHarness h("apex_nodes/BilateralFilter", {"image"}, "image");
  h.set("d", "7");
  h.set("sigma_color", "40");
  h.set("sigma_space", "20");
  h.set("border_type", "replicate");
  cv::Mat want, bgra;
  cv::bilateralFilter(src, want, 7, 40, 20, cv::BORDER_REPLICATE);
  expectResult(h, image(src, "bgr8"), want, "bgr8");
  cv::cvtColor(src, bgra, cv::COLOR_BGR2BGRA);
  expectError(h, image(bgra, "bgra8"), "cannot handle 4-channel images (encoding 'bgra8'); needs 1 or 3 channels");
}

TEST(ImageFilters, BoxFilterMatchesOpenCVNormalizedOrNot) {
  const cv::Mat src = gray("building.jpg");
  NodeHarness h("apex_nodes/BoxFilter", {"image"}, "image");
  h.set("ksize", "9");
  cv::Mat want;
  cv::boxFilter(src, want, -1, cv::Size(9, 9));
  expectResult(h, image(src, "mono8"), want, "mono8");
  h.set("normalize", "false");
  h.set("border_type", "constant");
  cv::boxFilter(src, want, -1, cv::Size(9, 9), cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
  expectResult(h, image(src, "mono8"), want, "mono8");
}

TEST(ImageFilters, SobelMatchesOpenCVWithTheEncodingOfItsDepth) {
  const cv::Mat src = gray("sudoku.png"), colour = load("sudoku.png");
  NodeHarness h("apex_nodes/Sobel", {"image"}, "image");  // dx 1, dy 0, ksize 3, ddepth 16S
  cv::Mat want, floats;
  cv::Sobel(src, want, CV_16S, 1, 0, 3);
  expectResult(h, image(src, "mono8"), want, "16SC1");
  h.set("dy", "2");
  h.set("ksize", "5");
  h.set("scale", "0.5");
  h.set("delta", "10");
  h.set("ddepth", "32F");
  h.set("border_type", "replicate");
  cv::Sobel(colour, want, CV_32F, 1, 2, 5, 0.5, 10, cv::BORDER_REPLICATE);
  expectResult(h, image(colour, "bgr8"), want, "32FC3");
  h.set("ddepth", "16S");
  src.convertTo(floats, CV_32F);
  expectError(h, image(floats, "32FC1"),
              "ddepth 16S cannot hold the derivatives of a 32F image ('32FC1'); choose 32F, 64F or same");
  h.set("dx", "0");
  h.set("dy", "0");
  expectError(h, image(src, "mono8"), "dx and dy are both 0");
}

TEST(ImageFilters, ScharrMatchesOpenCVAndTakesOneDerivative) {
  const cv::Mat src = gray("sudoku.png");
  NodeHarness h("apex_nodes/Scharr", {"image"}, "image");
  h.set("dx", "0");
  h.set("dy", "1");
  h.set("ddepth", "64F");
  cv::Mat want;
  cv::Scharr(src, want, CV_64F, 0, 1);
  expectResult(h, image(src, "mono8"), want, "64FC1");
  h.set("dx", "1");
  expectError(h, image(src, "mono8"), "Scharr takes one first derivative: dx = 1 or dy = 1, not dx = 1, dy = 1");
}

TEST(ImageFilters, LaplacianMatchesOpenCV) {
  const cv::Mat src = gray("building.jpg");
  NodeHarness h("apex_nodes/Laplacian", {"image"}, "image");  // ksize 1, ddepth 16S
  cv::Mat want;
  cv::Laplacian(src, want, CV_16S, 1);
  expectResult(h, image(src, "mono8"), want, "16SC1");
  h.set("ksize", "5");
  h.set("ddepth", "same");
  cv::Laplacian(src, want, -1, 5);
  expectResult(h, image(src, "mono8"), want, "mono8");
}

TEST(ImageFilters, EqualizeHistMatchesOpenCVOnGray8BitOnly) {
  const cv::Mat src = gray("home.jpg");
  NodeHarness h("apex_nodes/EqualizeHist", {"image"}, "image");
  cv::Mat want, wide;
  cv::equalizeHist(src, want);
  expectResult(h, image(src, "mono8"), want, "mono8");
  expectError(h, image(load("home.jpg"), "bgr8"),
              "cannot handle 3-channel images (encoding 'bgr8'); needs a single-channel image");
  src.convertTo(wide, CV_16U, 257);
  expectError(h, image(wide, "mono16"), "needs an 8-bit image ('mono16')");
}

TEST(ImageFilters, ClaheMatchesOpenCVOn8And16BitImages) {
  const cv::Mat src = gray("home.jpg");
  NodeHarness h("apex_nodes/CLAHE", {"image"}, "image");
  h.set("clip_limit", "3");
  h.set("tile_grid_size", "4");
  const cv::Ptr<cv::CLAHE> clahe = cv::createCLAHE(3, cv::Size(4, 4));
  cv::Mat want, wide, floats;
  clahe->apply(src, want);
  expectResult(h, image(src, "mono8"), want, "mono8");
  src.convertTo(wide, CV_16U, 257);
  clahe->apply(wide, want);
  expectResult(h, image(wide, "mono16"), want, "mono16");
  src.convertTo(floats, CV_32F);
  expectError(h, image(floats, "32FC1"), "needs an 8- or 16-bit image, got 32F ('32FC1')");
}

TEST(ImageFilters, NormalizeMatchesOpenCVToARangeOrANorm) {
  const cv::Mat colour = load("messi5.jpg");
  cv::Mat floats, want;
  gray("messi5.jpg").convertTo(floats, CV_32F, 1 / 255.0, 0.2);
  NodeHarness h("apex_nodes/Normalize", {"image"}, "image");  // minmax to [0, 255]
  h.set("dtype", "8U");
  cv::normalize(floats, want, 0, 255, cv::NORM_MINMAX, CV_8U);
  expectResult(h, image(floats, "32FC1"), want, "mono8");
  h.set("norm_type", "l2");
  h.set("alpha", "1");
  h.set("dtype", "32F");
  cv::normalize(colour, want, 1, 255, cv::NORM_L2, CV_32F);
  expectResult(h, image(colour, "bgr8"), want, "32FC3");
}

TEST(ImageFilters, ConvertScaleMatchesOpenCVAndKeepsTheColourOrder) {
  const cv::Mat colour = load("fruits.jpg"), src = gray("fruits.jpg");
  cv::Mat rgb, want, wide;
  cv::cvtColor(colour, rgb, cv::COLOR_BGR2RGB);
  NodeHarness h("apex_nodes/ConvertScale", {"image"}, "image");
  h.set("rtype", "16U");
  h.set("alpha", "256");
  colour.convertTo(want, CV_16U, 256);
  expectResult(h, image(colour, "bgr8"), want, "bgr16");
  rgb.convertTo(want, CV_16U, 256);
  expectResult(h, image(rgb, "rgb8"), want, "rgb16");
  h.set("rtype", "32F");
  h.set("alpha", "0.004");
  h.set("beta", "-0.5");
  src.convertTo(want, CV_32F, 0.004, -0.5);
  expectResult(h, image(src, "mono8"), want, "32FC1");
  src.convertTo(wide, CV_16U, 257);
  h.set("rtype", "8U");
  h.set("alpha", "0.00390625");
  h.set("beta", "0");
  wide.convertTo(want, CV_8U, 0.00390625);
  expectResult(h, image(wide, "mono16"), want, "mono8");
}

TEST(ImageFilters, FlipMatchesOpenCVForEachCode) {
  const cv::Mat src = load("messi5.jpg");
  NodeHarness h("apex_nodes/Flip", {"image"}, "image");
  for (const auto& [name, code] : std::vector<std::pair<std::string, int>>{{"horizontal", 1}, {"vertical", 0}, {"both", -1}}) {
    h.set("flip_code", name);
    cv::Mat want;
    cv::flip(src, want, code);
    expectResult(h, image(src, "bgr8"), want, "bgr8");
  }
}

TEST(ImageFilters, PyrDownAndPyrUpMatchOpenCV) {
  const cv::Mat src = load("sudoku.png");  // 558x563: odd rows
  cv::Mat want;
  NodeHarness down("apex_nodes/PyrDown", {"image"}, "image");
  cv::pyrDown(src, want);
  EXPECT_EQ(want.size(), cv::Size(279, 282));
  expectResult(down, image(src, "bgr8"), want, "bgr8");
  NodeHarness up("apex_nodes/PyrUp", {"image"}, "image");
  cv::pyrUp(gray("smarties.png"), want);
  EXPECT_EQ(want.size(), cv::Size(826, 712));
  expectResult(up, image(gray("smarties.png"), "mono8"), want, "mono8");
}

TEST(ImageFilters, WarpPerspectiveMatchesOpenCVOnARealHomography) {
  // graf1.png to graf3.png: opencv-doc's homography between two views of the same wall
  const cv::Mat src = load("graf1.png");
  cv::Mat H, want;
  cv::FileStorage(kData + "/H1to3p.xml", cv::FileStorage::READ)["H13"] >> H;
  ASSERT_EQ(H.size(), cv::Size(3, 3));
  ASSERT_EQ(H.type(), CV_64F);
  std::ostringstream m;
  m << std::setprecision(17) << "[";
  for (int i = 0; i < 9; ++i) m << (i ? ", " : "") << H.at<double>(i / 3, i % 3);
  m << "]";
  NodeHarness h("apex_nodes/WarpPerspective", {"image"}, "image");
  h.set("m", m.str());
  cv::warpPerspective(src, want, H, src.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  expectResult(h, image(src, "bgr8"), want, "bgr8");
  h.set("inverse_map", "true");
  h.set("width", "400");
  h.set("height", "300");
  h.set("interpolation", "nearest");
  h.set("border_mode", "replicate");
  cv::warpPerspective(src, want, H, cv::Size(400, 300), cv::INTER_NEAREST | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
  expectResult(h, image(src, "bgr8"), want, "bgr8");
  h.set("m", "[1, 0, 0, 0, 1, 0]");
  expectError(h, image(src, "bgr8"), "'m' takes nine numbers (the 3x3 matrix, row by row), not 6");
}

TEST(ImageFilters, DistanceTransformMatchesOpenCVAndSends32F) {
  cv::Mat binary, want;
  cv::threshold(gray("sudoku.png"), binary, 128, 255, cv::THRESH_BINARY);
  NodeHarness h("apex_nodes/DistanceTransform", {"image"}, "image");  // l2, mask 3
  cv::distanceTransform(binary, want, cv::DIST_L2, cv::DIST_MASK_3, CV_32F);
  expectResult(h, image(binary, "mono8"), want, "32FC1");
  h.set("mask_size", "precise");
  cv::distanceTransform(binary, want, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  expectResult(h, image(binary, "mono8"), want, "32FC1");
  h.set("distance_type", "l1");
  h.set("mask_size", "5");
  cv::distanceTransform(binary, want, cv::DIST_L1, cv::DIST_MASK_5, CV_32F);
  expectResult(h, image(binary, "mono8"), want, "32FC1");
  expectError(h, image(load("sudoku.png"), "bgr8"),
              "cannot handle 3-channel images (encoding 'bgr8'); needs a single-channel image");
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
