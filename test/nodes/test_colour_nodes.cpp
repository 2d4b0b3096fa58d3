// Colour and combining nodes (colour.cpp, combine.cpp) on opencv-doc's real images, against the
// same OpenCV calls made directly (pixel-exact, encoding and header too), and their errors on
// input they cannot handle: wrong encodings, channel counts, sizes that do not match.
#include <gmock/gmock.h>

#include <functional>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "apex_nodes/types.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;

namespace {

TEST(ColourNodes, ColorRangeMatchesInRangeInEachSpaceForBgrAndRgbImages) {
  const cv::Mat bgr = readData("smarties.png");
  cv::Mat rgb, want;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  NodeHarness h("apex_nodes/ColorRange", {"image"}, "mask");
  struct Case {
    const char* space;
    int code;  // -1: none
    cv::Scalar lower, upper;
  };
  for (const Case& c : {Case{"bgr", -1, {0, 0, 100}, {90, 90, 255}},  // reds
                        Case{"hsv", cv::COLOR_BGR2HSV, {0, 150, 100}, {179, 255, 255}},  // saturated colours
                        Case{"lab", cv::COLOR_BGR2Lab, {0, 140, 0}, {255, 255, 255}}}) {
    h.set("color_space", c.space);
    h.set("lower",
          "[" + std::to_string(c.lower[0]) + ", " + std::to_string(c.lower[1]) + ", " + std::to_string(c.lower[2]) + "]");
    h.set("upper",
          "[" + std::to_string(c.upper[0]) + ", " + std::to_string(c.upper[1]) + ", " + std::to_string(c.upper[2]) + "]");
    cv::Mat converted;  // new per case: converting into one that shares bgr's pixels would overwrite them
    if (c.code < 0) converted = bgr;
    else cv::cvtColor(bgr, converted, c.code);
    cv::inRange(converted, c.lower, c.upper, want);
    EXPECT_GT(cv::countNonZero(want), 0) << c.space;  // the range picks some pixels, not all
    EXPECT_LT(cv::countNonZero(want), static_cast<int>(want.total())) << c.space;
    SCOPED_TRACE(c.space);
    expectImage(h, runImages(h, {imageOf(bgr, "bgr8")}), want, "mono8");
    expectImage(h, runImages(h, {imageOf(rgb, "rgb8")}), want, "mono8");  // the same colours, in the other order
  }
}

TEST(ColourNodes, ColorRangeRefusesImagesOfUnknownColourOrder) {
  const cv::Mat bgr = readData("smarties.png");
  NodeHarness h("apex_nodes/ColorRange", {"image"}, "mask");
  expectNothing(h, runImages(h, {imageOf(readGrayData("smarties.png"), "mono8")}),
                "cannot handle 1-channel images (encoding 'mono8'); needs 3 channels");
  expectNothing(h, runImages(h, {imageOf(bgr, "8UC3")}), "needs a bgr8 or rgb8 image, got '8UC3'");
  h.set("lower", "[10, 20]");
  expectNothing(h, runImages(h, {imageOf(bgr, "bgr8")}), "'lower' takes three numbers, one per channel, not 2");
}

TEST(ColourNodes, SplitChannelsSendsEachChannelAndNothingForChannelsTheImageLacks) {
  const cv::Mat bgr = readData("baboon.jpg");
  std::vector<cv::Mat> planes;
  cv::split(bgr, planes);
  for (int c = 0; c < 3; ++c) {
    NodeHarness h("apex_nodes/SplitChannels", {"image"}, "channel_" + std::to_string(c));
    expectImage(h, runImages(h, {imageOf(bgr, "bgr8")}), planes[c], "mono8");
  }
  NodeHarness alpha("apex_nodes/SplitChannels", {"image"}, "channel_3");
  EXPECT_TRUE(runImages(alpha, {imageOf(bgr, "bgr8")}).isNothing());
  EXPECT_EQ(alpha.error(), "");  // no fourth channel: Nothing, not an error
  cv::Mat bgra, wide;
  cv::merge(std::vector<cv::Mat>{planes[0], planes[1], planes[2], readGrayData("baboon.jpg")}, bgra);
  expectImage(alpha, runImages(alpha, {imageOf(bgra, "bgra8")}), readGrayData("baboon.jpg"), "mono8");
  NodeHarness green("apex_nodes/SplitChannels", {"image"}, "channel_1");
  bgr.convertTo(wide, CV_16U, 257);
  planes[1].convertTo(planes[1], CV_16U, 257);
  expectImage(green, runImages(green, {imageOf(wide, "bgr16")}), planes[1], "mono16");
}

TEST(ColourNodes, MergeChannelsMakesBgrOrBgraOfSingleChannelImages) {
  const cv::Mat bgr = readData("fruits.jpg");
  std::vector<cv::Mat> planes;
  cv::split(bgr, planes);
  NodeHarness h("apex_nodes/MergeChannels", {"channel_0", "channel_1", "channel_2"}, "image");  // channel_3 unconnected
  expectImage(h, runImages(h, {imageOf(planes[0], "mono8"), imageOf(planes[1], "mono8"), imageOf(planes[2], "mono8")}), bgr,
              "bgr8");
  std::vector<cv::Mat> wide(3);
  cv::Mat want;
  for (int c = 0; c < 3; ++c) planes[c].convertTo(wide[c], CV_16U, 257);
  cv::merge(wide, want);
  expectImage(h, runImages(h, {imageOf(wide[0], "mono16"), imageOf(wide[1], "mono16"), imageOf(wide[2], "mono16")}), want,
              "bgr16");

  NodeHarness four("apex_nodes/MergeChannels", {"channel_0", "channel_1", "channel_2", "channel_3"}, "image");
  const cv::Mat alpha = readGrayData("fruits.jpg");
  cv::merge(std::vector<cv::Mat>{planes[0], planes[1], planes[2], alpha}, want);
  expectImage(four,
              runImages(four, {imageOf(planes[0], "mono8"), imageOf(planes[1], "mono8"), imageOf(planes[2], "mono8"),
                               imageOf(alpha, "mono8")}),
              want, "bgra8");
}

TEST(ColourNodes, MergeChannelsNamesTheChannelThatDoesNotFit) {
  const cv::Mat bgr = readData("fruits.jpg");
  std::vector<cv::Mat> planes;
  cv::split(bgr, planes);
  cv::Mat half, wide;
  cv::resize(planes[1], half, cv::Size(256, 240));
  NodeHarness h("apex_nodes/MergeChannels", {"channel_0", "channel_1", "channel_2"}, "image");
  expectNothing(
      h, runImages(h, {imageOf(planes[0], "mono8"), imageOf(half, "mono8"), imageOf(planes[2], "mono8")}),
      "channel_1 is 256x240 'mono8' (8UC1), channel_0 512x480 'mono8' (8UC1): the channels need the same size and depth");
  planes[2].convertTo(wide, CV_16U, 257);
  expectNothing(h, runImages(h, {imageOf(planes[0], "mono8"), imageOf(planes[1], "mono8"), imageOf(wide, "mono16")}),
                "channel_2 is 512x480 'mono16' (16UC1), channel_0 512x480 'mono8' (8UC1)");
  expectNothing(h, runImages(h, {imageOf(planes[0], "mono8"), imageOf(bgr, "bgr8"), imageOf(planes[2], "mono8")}),
                "channel_1 is 512x480 'bgr8' (8UC3); each input needs a single-channel image");
}

/** `bgr` as a camera's raw Bayer mosaic: each pixel keeps the colour `pattern` gives its place
 *  ("rggb": red, green on even rows; green, blue on odd ones). */
template <class Pixel>
cv::Mat mosaic(const cv::Mat& bgr, const std::string& pattern) {
  cv::Mat out(bgr.size(), CV_MAKETYPE(bgr.depth(), 1));
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x) {
      const char colour = pattern[(y % 2) * 2 + x % 2];
      out.at<Pixel>(y, x) = bgr.at<cv::Vec<Pixel, 3>>(y, x)[colour == 'b' ? 0 : colour == 'g' ? 1 : 2];
    }
  return out;
}

TEST(ColourNodes, DebayerMatchesOpenCVForEachPatternAndMethod) {
  const cv::Mat bgr = readData("fruits.jpg");
  NodeHarness h("apex_nodes/Debayer", {"image"}, "image");
  // each pattern with the one that swaps red and blue: read so, the colours come out wrong
  const std::map<std::string, std::pair<int, int>> codes{{"rggb", {cv::COLOR_BayerRGGB2BGR, cv::COLOR_BayerBGGR2BGR}},
                                                         {"bggr", {cv::COLOR_BayerBGGR2BGR, cv::COLOR_BayerRGGB2BGR}},
                                                         {"gbrg", {cv::COLOR_BayerGBRG2BGR, cv::COLOR_BayerGRBG2BGR}},
                                                         {"grbg", {cv::COLOR_BayerGRBG2BGR, cv::COLOR_BayerGBRG2BGR}}};
  cv::Mat want, swapped;
  for (const auto& [pattern, code] : codes) {
    const cv::Mat raw = mosaic<uchar>(bgr, pattern);
    cv::cvtColor(raw, want, code.first);
    cv::cvtColor(raw, swapped, code.second);
    EXPECT_LT(cv::norm(want, bgr, cv::NORM_L1), cv::norm(swapped, bgr, cv::NORM_L1)) << pattern;  // the codes mean what ROS means
    expectImage(h, runImages(h, {imageOf(raw, "bayer_" + pattern + "8")}), want, "bgr8");
  }
  const cv::Mat raw = mosaic<uchar>(bgr, "grbg");
  h.set("method", "vng");
  cv::cvtColor(raw, want, cv::COLOR_BayerGRBG2BGR_VNG);
  expectImage(h, runImages(h, {imageOf(raw, "bayer_grbg8")}), want, "bgr8");
  h.set("method", "ea");
  cv::cvtColor(raw, want, cv::COLOR_BayerGRBG2BGR_EA);
  expectImage(h, runImages(h, {imageOf(raw, "bayer_grbg8")}), want, "bgr8");
}

TEST(ColourNodes, DebayerTakes16BitMosaicsAndNamesWhatItCannotRead) {
  cv::Mat wide, want;
  readData("fruits.jpg").convertTo(wide, CV_16U, 257);
  const cv::Mat raw = mosaic<ushort>(wide, "bggr");
  NodeHarness h("apex_nodes/Debayer", {"image"}, "image");
  cv::cvtColor(raw, want, cv::COLOR_BayerBGGR2BGR);
  expectImage(h, runImages(h, {imageOf(raw, "bayer_bggr16")}), want, "bgr16");
  h.set("method", "ea");
  cv::cvtColor(raw, want, cv::COLOR_BayerBGGR2BGR_EA);
  expectImage(h, runImages(h, {imageOf(raw, "bayer_bggr16")}), want, "bgr16");
  h.set("method", "vng");
  expectNothing(h, runImages(h, {imageOf(raw, "bayer_bggr16")}),
                "vng demosaics 8-bit mosaics only, not 'bayer_bggr16': choose bilinear or ea");
  h.set("method", "bilinear");
  const std::string accepted = "needs bayer_rggb8, bayer_bggr8, bayer_gbrg8 or bayer_grbg8, or their 16-bit forms";
  expectNothing(h, runImages(h, {readDataImage("fruits.jpg")}), "cannot debayer 'bgr8'; " + accepted);
  expectNothing(h, runImages(h, {imageOf(readGrayData("fruits.jpg"), "mono8")}), "cannot debayer 'mono8'; " + accepted);
  expectNothing(h, runImages(h, {imageOf(readGrayData("fruits.jpg"), "bayer_rggb16")}),
                "the encoding 'bayer_rggb16' does not fit the image's pixels, 1-channel 8U");
}

TEST(CombineNodes, ImageCombineMatchesOpenCVForEachOperation) {
  const cv::Mat a = readData("graf1.png"), b = readData("graf3.png");
  NodeHarness h("apex_nodes/ImageCombine", {"a", "b"}, "image");
  h.set("alpha", "0.3");
  h.set("beta", "0.6");
  h.set("gamma", "12");
  using Op = std::function<void(const cv::Mat&, const cv::Mat&, cv::Mat&)>;
  const std::vector<std::pair<std::string, Op>> ops{
      {"add", [](const cv::Mat& x, const cv::Mat& y, cv::Mat& o) { cv::add(x, y, o); }},
      {"subtract", [](const cv::Mat& x, const cv::Mat& y, cv::Mat& o) { cv::subtract(x, y, o); }},
      {"absdiff", [](const cv::Mat& x, const cv::Mat& y, cv::Mat& o) { cv::absdiff(x, y, o); }},
      {"and", [](const cv::Mat& x, const cv::Mat& y, cv::Mat& o) { cv::bitwise_and(x, y, o); }},
      {"or", [](const cv::Mat& x, const cv::Mat& y, cv::Mat& o) { cv::bitwise_or(x, y, o); }},
      {"xor", [](const cv::Mat& x, const cv::Mat& y, cv::Mat& o) { cv::bitwise_xor(x, y, o); }},
      {"min", [](const cv::Mat& x, const cv::Mat& y, cv::Mat& o) { cv::min(x, y, o); }},
      {"max", [](const cv::Mat& x, const cv::Mat& y, cv::Mat& o) { cv::max(x, y, o); }},
      {"weighted", [](const cv::Mat& x, const cv::Mat& y, cv::Mat& o) { cv::addWeighted(x, 0.3, y, 0.6, 12, o); }}};
  for (const auto& [name, op] : ops) {
    h.set("operation", name);
    cv::Mat want;
    op(a, b, want);
    SCOPED_TRACE(name);
    expectImage(h, runImages(h, {imageOf(a, "bgr8"), imageOf(b, "bgr8")}), want, "bgr8");
  }
}

TEST(CombineNodes, ImageCombineNamesBothImagesWhenTheyDoNotMatch) {
  const cv::Mat a = readData("graf1.png");
  NodeHarness h("apex_nodes/ImageCombine", {"a", "b"}, "image");
  h.set("operation", "absdiff");
  expectNothing(h, runImages(h, {imageOf(a, "bgr8"), readDataImage("baboon.jpg")}),
                "a is 800x640 'bgr8' (8UC3), b 512x512 'bgr8' (8UC3): absdiff needs two images of the same size and type");
  expectNothing(h, runImages(h, {imageOf(a, "bgr8"), imageOf(readGrayData("graf3.png"), "mono8")}),
                "a is 800x640 'bgr8' (8UC3), b 800x640 'mono8' (8UC1)");
}

TEST(CombineNodes, ApplyMaskKeepsThePixelsUnderTheMask) {
  const cv::Mat src = readData("fruits.jpg");
  cv::Mat mask, inverse;
  cv::threshold(readGrayData("fruits.jpg"), mask, 128, 255, cv::THRESH_BINARY);
  cv::bitwise_not(mask, inverse);
  NodeHarness h("apex_nodes/ApplyMask", {"image", "mask"}, "image");
  for (const cv::Mat& m : {mask, inverse}) {
    cv::Mat want = cv::Mat::zeros(src.size(), src.type());
    src.copyTo(want, m);
    expectImage(h, runImages(h, {imageOf(src, "bgr8"), imageOf(m, "mono8")}), want, "bgr8");
  }
}

TEST(CombineNodes, ApplyMaskNeedsAMono8MaskOfTheImagesSize) {
  const cv::Mat src = readData("fruits.jpg");
  cv::Mat half;
  cv::resize(readGrayData("fruits.jpg"), half, cv::Size(256, 240));
  NodeHarness h("apex_nodes/ApplyMask", {"image", "mask"}, "image");
  expectNothing(h, runImages(h, {imageOf(src, "bgr8"), imageOf(src, "bgr8")}),
                "the mask is 512x480 'bgr8' (8UC3); it needs a single-channel 8-bit image (mono8)");
  expectNothing(h, runImages(h, {imageOf(src, "bgr8"), imageOf(half, "mono8")}),
                "the image is 512x480 'bgr8' (8UC3), the mask 256x240 'mono8' (8UC1): they need the same size");
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
