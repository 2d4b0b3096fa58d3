// ximgproc's nodes (ximgproc_filters.cpp, ximgproc_shapes.cpp) on opencv-doc's real images, against
// the same cv::ximgproc call made directly: pixel- or segment-exact, each call being repeatable
// (single-threaded, or split by rows with nothing summed across them), and each node's error on
// input it cannot handle.
#include <gmock/gmock.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>
#include <string>
#include <utility>
#include <vector>

#include "apex_nodes/shapes.hpp"
#include "apex_nodes/types.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;
using apex_nodes::Image;
using apex_nodes::Lines;
namespace xi = cv::ximgproc;

namespace {

TEST(XimgprocNodes, GuidedFilterMatchesOpenCVGuidedByTheImageItselfOrByAGuide) {
  const cv::Mat src = readData("fruits.jpg"), gray = readGrayData("fruits.jpg");
  NodeHarness self("apex_nodes/GuidedFilter", {"image"}, "image");  // radius 4, eps 400, ddepth same; no guide
  cv::Mat want;
  xi::guidedFilter(src, src, want, 4, 400.0);
  EXPECT_GT(cv::norm(want, src, cv::NORM_INF), 0.0) << "the call changed nothing: a test of nothing";
  expectImage(self, self.run(imageOf(src, "bgr8")), want, "bgr8");
  self.set("radius", "8");
  self.set("eps", "100");
  self.set("ddepth", "32F");
  xi::guidedFilter(src, src, want, 8, 100.0, CV_32F);
  expectImage(self, self.run(imageOf(src, "bgr8")), want, "32FC3");
  cv::Mat wide;
  gray.convertTo(wide, CV_16U, 257);
  expectNothing(self, self.run(imageOf(wide, "mono16")), "the image is 512x480 'mono16' (16UC1); it needs 8-bit or 32F pixels");

  NodeHarness guided("apex_nodes/GuidedFilter", {"image", "guide"}, "image");  // the colours smoothed along the gray's edges
  xi::guidedFilter(gray, src, want, 4, 400.0);
  expectImage(guided, runImages(guided, {imageOf(src, "bgr8"), imageOf(gray, "mono8")}), want, "bgr8");
  cv::Mat half;
  cv::resize(gray, half, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
  expectNothing(guided, runImages(guided, {imageOf(src, "bgr8"), imageOf(half, "mono8")}),
                "the guide is 256x240 'mono8' (8UC1), the image 512x480 'bgr8' (8UC3): they need the same size");
}

TEST(XimgprocNodes, AnisotropicDiffusionMatchesOpenCVAndSendsTheFrameItselfAfterNoIterations) {
  const cv::Mat src = readData("baboon.jpg");
  NodeHarness h("apex_nodes/AnisotropicDiffusion", {"image"}, "image");  // alpha 0.1, k 0.02, niters 10
  cv::Mat want;
  xi::anisotropicDiffusion(src, want, 0.1f, 0.02f, 10);
  EXPECT_GT(cv::norm(want, src, cv::NORM_INF), 0.0);
  expectImage(h, h.run(imageOf(src, "bgr8")), want, "bgr8");
  h.set("alpha", "0.25");
  h.set("k", "0.05");
  h.set("niters", "3");
  xi::anisotropicDiffusion(src, want, 0.25f, 0.05f, 3);
  expectImage(h, h.run(imageOf(src, "bgr8")), want, "bgr8");
  h.set("niters", "0");  // OpenCV copies the image: the node sends the frame's own message
  const auto frame = imageOf(src, "bgr8");
  EXPECT_EQ(h.run(frame).as<Image>(), frame);
  expectNothing(h, h.run(imageOf(readGrayData("baboon.jpg"), "mono8")),
                "cannot handle 1-channel images (encoding 'mono8'); needs 3 channels");
}

TEST(XimgprocNodes, EdgePreservingFilterMatchesOpenCV) {
  const cv::Rect patch(192, 320, 128, 96);  // a patch: the filter blurs a window around every pixel, one thread
  const cv::Mat src = readData("baboon.jpg")(patch).clone(), gray = readGrayData("baboon.jpg")(patch).clone();
  NodeHarness h("apex_nodes/EdgePreservingFilter", {"image"}, "image");  // d 9, threshold 20
  cv::Mat want;
  xi::edgePreservingFilter(src, want, 9, 20.0);
  EXPECT_GT(cv::norm(want, src, cv::NORM_INF), 0.0);
  expectImage(h, h.run(imageOf(src, "bgr8")), want, "bgr8");
  h.set("d", "5");
  h.set("threshold", "40");
  xi::edgePreservingFilter(src, want, 5, 40.0);
  expectImage(h, h.run(imageOf(src, "bgr8")), want, "bgr8");
  expectNothing(h, h.run(imageOf(gray, "mono8")), "cannot handle 1-channel images (encoding 'mono8'); needs 3 channels");
}

TEST(XimgprocNodes, NiblackThresholdMatchesOpenCVWithEachMethod) {
  const cv::Mat page = readGrayData("imageTextN.png");
  NodeHarness h("apex_nodes/NiblackThreshold", {"image"}, "image");  // binary 255, block 25, k -0.2, niblack, r 128
  cv::Mat want;
  xi::niBlackThreshold(page, want, 255, cv::THRESH_BINARY, 25, -0.2, xi::BINARIZATION_NIBLACK, 128);
  EXPECT_GT(cv::countNonZero(want), 0);
  EXPECT_LT(cv::countNonZero(want), int(page.total()));
  expectImage(h, h.run(imageOf(page, "mono8")), want, "mono8");
  h.set("type", "binary_inv");
  h.set("max_value", "200");
  h.set("block_size", "31");
  h.set("k", "0.3");
  h.set("r", "100");
  for (const auto& [name, method] : std::vector<std::pair<std::string, int>>{
           {"sauvola", xi::BINARIZATION_SAUVOLA}, {"wolf", xi::BINARIZATION_WOLF}, {"nick", xi::BINARIZATION_NICK}}) {
    h.set("binarization_method", name);
    xi::niBlackThreshold(page, want, 200, cv::THRESH_BINARY_INV, 31, 0.3, method, 100);
    expectImage(h, h.run(imageOf(page, "mono8")), want, "mono8");
  }
  expectNothing(h, h.run(readDataImage("imageTextN.png")),
                "cannot handle 3-channel images (encoding 'bgr8'); needs a single-channel image");
}

TEST(XimgprocNodes, ThinningMatchesOpenCVWithEitherAlgorithm) {
  cv::Mat shapes, want;
  cv::threshold(readGrayData("pic1.png"), shapes, 128, 255, cv::THRESH_BINARY_INV);  // black shapes on white: white on black
  NodeHarness h("apex_nodes/Thinning", {"image"}, "image");  // zhangsuen
  xi::thinning(shapes, want, xi::THINNING_ZHANGSUEN);
  EXPECT_LT(cv::countNonZero(want), cv::countNonZero(shapes) / 10) << "hardly thinned: not the shapes meant";
  expectImage(h, h.run(imageOf(shapes, "mono8")), want, "mono8");
  h.set("thinning_type", "guohall");
  xi::thinning(shapes, want, xi::THINNING_GUOHALL);
  expectImage(h, h.run(imageOf(shapes, "mono8")), want, "mono8");
  expectNothing(h, h.run(readDataImage("pic1.png")),
                "cannot handle 3-channel images (encoding 'bgr8'); needs a single-channel image");
}

/** The segments cv::ximgproc's FastLineDetector finds in `gray` (which it may clear: give a copy). */
std::vector<cv::Vec4f> fastLines(const cv::Mat& gray, int length, float distance, double th1, double th2, int aperture,
                                 bool merge) {
  std::vector<cv::Vec4f> lines;
  xi::createFastLineDetector(length, distance, th1, th2, aperture, merge)->detect(gray, lines);
  return lines;
}

/** Expects `m`, what `h`'s node sent, to be `want` found in an image of `size` with imageOf's header. */
void expectLines(NodeHarness& h, const Message& m, const std::vector<cv::Vec4f>& want, const cv::Size& size) {
  const auto got = m.as<Lines>();
  ASSERT_TRUE(got) << "the node sent no lines: " << h.error();
  expectCameraHeader(got->header);
  EXPECT_EQ(got->image_size, size);
  EXPECT_EQ(got->lines, want);
}

TEST(XimgprocNodes, FastLineDetectorMatchesOpenCVAndLeavesAnEdgeImageAsItCame) {
  const cv::Mat gray = readGrayData("building.jpg");
  NodeHarness h("apex_nodes/FastLineDetector", {"image"}, "lines");  // 10, 1.414213562, 50, 50, aperture 3, no merging
  const auto want = fastLines(gray, 10, 1.414213562f, 50, 50, 3, false);
  EXPECT_GT(want.size(), 50u);
  expectLines(h, h.run(imageOf(gray, "mono8")), want, gray.size());
  h.set("length_threshold", "30");
  h.set("distance_threshold", "2");
  h.set("canny_th1", "80");
  h.set("canny_th2", "160");
  h.set("do_merge", "true");
  expectLines(h, h.run(imageOf(gray, "mono8")), fastLines(gray, 30, 2.0f, 80, 160, 3, true), gray.size());

  cv::Mat edges;  // an edge image, no Canny: the detector clears the edges it follows, so the node works on a copy
  cv::Canny(gray, edges, 50, 150);
  const cv::Mat as_sent = edges.clone();
  h.set("canny_aperture_size", "0");
  expectLines(h, h.run(imageOf(edges, "mono8")), fastLines(as_sent.clone(), 30, 2.0f, 80, 160, 0, true), gray.size());
  expectSameMat(edges, as_sent);
  expectNothing(h, h.run(readDataImage("building.jpg")),
                "cannot handle 3-channel images (encoding 'bgr8'); needs a single-channel image");
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
