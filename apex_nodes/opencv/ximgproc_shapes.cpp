// Binary images and lines from OpenCV contrib's ximgproc: NiblackThreshold (a local threshold for
// text and unevenly lit pages), Thinning (a binary image's skeleton) and FastLineDetector (line
// segments, sent as HoughLines sends them).
#include <opencv2/ximgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_filter.hpp"
#include "apex_nodes/shapes.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace xi = cv::ximgproc;

class NiblackThreshold : public ImageFilter {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "single-channel 8-bit"};
  static inline const apex::OutputPort<Image> kBinary{"image", "mono8: binary (0 or max_value) unless type says otherwise"};
  static inline const apex::ParamDecl<double> kMaxValue =
      param::number("max_value").range(0.0, 255.0).step(1.0).init(255.0).describe("value of pixels that pass (binary types)");
  static inline const apex::ChoiceDecl<int> kType = param::choice<int>("type", {{"binary", cv::THRESH_BINARY},
                                                                                {"binary_inv", cv::THRESH_BINARY_INV},
                                                                                {"trunc", cv::THRESH_TRUNC},
                                                                                {"tozero", cv::THRESH_TOZERO},
                                                                                {"tozero_inv", cv::THRESH_TOZERO_INV}});
  static inline const apex::ParamDecl<int> kBlockSize =
      param::integer("block_size").range(3, 255).step(2).init(25).describe("neighbourhood width and height in pixels, odd");
  static inline const apex::ParamDecl<double> kK = param::number("k").range(-2.0, 2.0).step(0.01).init(-0.2).describe(
      "the methods' factor (niblack: about -0.2, sauvola: 0.2 to 0.5)");
  static inline const apex::ChoiceDecl<int> kMethod =
      param::choice<int>("binarization_method",
                         {{"niblack", xi::BINARIZATION_NIBLACK, "mean + k x deviation"},
                          {"sauvola", xi::BINARIZATION_SAUVOLA, "mean x (1 + k x (deviation / r - 1))"},
                          {"wolf", xi::BINARIZATION_WOLF,
                           "mean - k x (1 - deviation / the image's largest deviation) x (mean - the image's darkest pixel)"},
                          {"nick", xi::BINARIZATION_NICK, "mean + k x the root of (variance + the mean of the squares)"}})
          .describe("how each pixel's threshold comes from its neighbourhood's mean and deviation");
  static inline const apex::ParamDecl<double> kR =
      param::number("r").range(1.0, 255.0).step(1.0).init(128.0).describe("sauvola: the deviation's dynamic range");
  static apex::Manifest manifest() {
    return filterManifest(
               "Thresholds each pixel against its neighbourhood's mean and deviation (Niblack, Sauvola, Wolf, NICK; "
               "cv::ximgproc::niBlackThreshold): text on unevenly lit pages",
               kImage, kBinary)
        .param(kMaxValue)
        .param(kType)
        .param(kBlockSize)
        .param(kK)
        .param(kMethod)
        .param(kR);
  }
  NiblackThreshold() : ImageFilter("1", true, kImage, kBinary) {}

 private:
  void filter(const Image& in, Image& out) override {
    xi::niBlackThreshold(in.mat, out.mat, max_value_.get(), type_.get(), block_size_.get(), k_.get(), method_.get(), r_.get());
    out.encoding = "mono8";
  }
  apex::Param<double> max_value_{this, kMaxValue};
  apex::Choice<int> type_{this, kType};
  apex::Param<int> block_size_{this, kBlockSize};
  apex::Param<double> k_{this, kK};
  apex::Choice<int> method_{this, kMethod};
  apex::Param<double> r_{this, kR};
};

class Thinning : public ImageFilter {
 public:
  static inline const apex::InputPort<Image> kImage{
      "image", "binary mono8: 255 on the shapes, 0 around (a pixel from 128 up counts as shape)"};
  static inline const apex::OutputPort<Image> kSkeleton{"image", "mono8: the shapes' skeletons, lines one pixel wide, 255 on 0"};
  static inline const apex::ChoiceDecl<int> kThinningType =
      param::choice<int>("thinning_type",
                         {{"zhangsuen", xi::THINNING_ZHANGSUEN, "Zhang-Suen"}, {"guohall", xi::THINNING_GUOHALL, "Guo-Hall"}})
          .describe("the algorithm");
  static apex::Manifest manifest() {
    return filterManifest("Thins the shapes of a binary image to their skeletons (cv::ximgproc::thinning)", kImage, kSkeleton)
        .param(kThinningType);
  }
  Thinning() : ImageFilter("1", true, kImage, kSkeleton) {}

 private:
  void filter(const Image& in, Image& out) override {
    xi::thinning(in.mat, out.mat, thinning_type_.get());
    out.encoding = "mono8";
  }
  apex::Choice<int> thinning_type_{this, kThinningType};
};

class FastLineDetector : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "single-channel 8-bit gray (edges, with canny_aperture_size 0)"};
  static inline const apex::OutputPort<Lines> kLines{"lines", "segments: x1, y1, x2, y2, the brighter side on their left"};
  static inline const apex::ParamDecl<int> kLengthThreshold =
      param::integer("length_threshold").range(1, 10000).step(1).init(10).describe("pixels; shorter segments are dropped");
  static inline const apex::ParamDecl<double> kDistanceThreshold =
      param::number("distance_threshold")
          .range(0.01, 100.0)
          .step(0.01)
          .init(1.414213562)
          .describe("pixels: an edge point farther than this from a segment's line is an outlier");
  static inline const apex::ParamDecl<double> kCannyTh1 =
      param::number("canny_th1").range(1.0, 1000.0).step(1.0).init(50.0).describe("Canny's first hysteresis threshold");
  static inline const apex::ParamDecl<double> kCannyTh2 =
      param::number("canny_th2").range(1.0, 1000.0).step(1.0).init(50.0).describe("Canny's second hysteresis threshold");
  static inline const apex::ChoiceDecl<int> kCannyApertureSize =
      param::choice<int>("canny_aperture_size",
                         {{"0", 0, "no Canny: the image is an edge image already"}, {"3", 3}, {"5", 5}, {"7", 7}})
          .init("3")
          .describe("Canny's Sobel aperture");
  static inline const apex::ParamDecl<bool> kDoMerge =
      param::flag("do_merge").describe("join segments that continue one another");
  static apex::Manifest manifest() {
    return apex::Manifest("Finds line segments in a gray image (Lee's fast line detector, cv::ximgproc::FastLineDetector)")
        .inCategory("detection")
        .input(kImage)
        .output(kLines)
        .param(kLengthThreshold)
        .param(kDistanceThreshold)
        .param(kCannyTh1)
        .param(kCannyTh2)
        .param(kCannyApertureSize)
        .param(kDoMerge);
  }
  void process() override {
    const Image& in = *image_.get();
    requireImage(in, "1");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("the image is " + imageWords(in) + "; it needs 8-bit pixels");
    if (in.mat.cols < 6 || in.mat.rows < 6)  // the detector clears a 6x6 corner of its edges
      throw std::invalid_argument("the image is " + imageWords(in) + "; it needs 6x6 pixels at least");
    const int aperture = canny_aperture_size_.get();
    const auto detector = xi::createFastLineDetector(length_threshold_.get(), float(distance_threshold_.get()), canny_th1_.get(),
                                                     canny_th2_.get(), aperture, do_merge_.get());
    auto out = std::make_shared<Lines>();
    out->header = in.header;
    out->image_size = in.mat.size();
    if (aperture == 0) {  // the detector clears the edge image as it follows it: a copy, the message's pixels untouched
      in.mat.copyTo(edges_);
      detector->detect(edges_, out->lines);
    } else {
      detector->detect(in.mat, out->lines);
    }
    lines_.publish(std::move(out));
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Output<Lines> lines_{this, kLines};
  apex::Param<int> length_threshold_{this, kLengthThreshold};
  apex::Param<double> distance_threshold_{this, kDistanceThreshold};
  apex::Param<double> canny_th1_{this, kCannyTh1};
  apex::Param<double> canny_th2_{this, kCannyTh2};
  apex::Choice<int> canny_aperture_size_{this, kCannyApertureSize};
  apex::Param<bool> do_merge_{this, kDoMerge};
  cv::Mat edges_;  // the copy detect() may clear, kept between frames
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::NiblackThreshold, "apex_nodes/NiblackThreshold");
APEX_REGISTER_NODE(apex_nodes::Thinning, "apex_nodes/Thinning");
APEX_REGISTER_NODE(apex_nodes::FastLineDetector, "apex_nodes/FastLineDetector");
