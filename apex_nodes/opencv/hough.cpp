// Hough transforms: HoughLines (probabilistic, line segments) and HoughCircles.
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/shapes.hpp"

namespace apex_nodes {
namespace param = apex::param;

namespace {
const char* const kCategory = "detection";

void requireGray8(const Image& in) {
  requireImage(in, "1");
  if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image, got '" + in.encoding + "'");
}
}  // namespace

class HoughLines : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "single-channel 8-bit, typically Canny's edges"};
  static inline const apex::OutputPort<Lines> kLines{"lines", "segments: x1, y1, x2, y2"};
  static inline const apex::ParamDecl<double> kRho =
      param::number("rho").range(0.1, 100.0).step(0.1).init(1.0).describe("the accumulator's distance resolution, pixels");
  static inline const apex::ParamDecl<double> kTheta =
      param::number("theta").range(0.01, 90.0).step(0.01).init(1.0).describe("the accumulator's angle resolution, degrees");
  static inline const apex::ParamDecl<int> kThreshold =
      param::integer("threshold").range(1, 10000).step(1).init(50).describe("votes a line needs");
  static inline const apex::ParamDecl<double> kMinLength =
      param::number("min_line_length").range(0.0, 10000.0).step(1.0).init(50.0).describe("pixels; shorter segments are dropped");
  static inline const apex::ParamDecl<double> kMaxGap =
      param::number("max_line_gap").range(0.0, 10000.0).step(1.0).init(10.0).describe("pixels: the largest gap joined");
  static apex::Manifest manifest() {
    return apex::Manifest("Finds line segments in an edge image (probabilistic Hough transform, cv::HoughLinesP)")
        .inCategory(kCategory)
        .input(kImage)
        .output(kLines)
        .param(kRho)
        .param(kTheta)
        .param(kThreshold)
        .param(kMinLength)
        .param(kMaxGap);
  }
  void process() override {
    const Image& in = *image_.get();
    requireGray8(in);
    std::vector<cv::Vec4i> found;
    cv::HoughLinesP(in.mat, found, rho_.get(), theta_.get() * CV_PI / 180, threshold_.get(), min_length_.get(), max_gap_.get());
    auto out = std::make_shared<Lines>();
    out->header = in.header;
    out->image_size = in.mat.size();
    out->lines.assign(found.begin(), found.end());
    lines_.publish(std::move(out));
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Output<Lines> lines_{this, kLines};
  apex::Param<double> rho_{this, kRho};
  apex::Param<double> theta_{this, kTheta};
  apex::Param<int> threshold_{this, kThreshold};
  apex::Param<double> min_length_{this, kMinLength};
  apex::Param<double> max_gap_{this, kMaxGap};
};

class HoughCircles : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "single-channel 8-bit gray (smoothed: e.g. a median blur)"};
  static inline const apex::OutputPort<Circles> kCircles{"circles", "centre x, y and radius each"};
  static inline const apex::ChoiceDecl<bool> kMethod =
      param::choice<bool>("method", {{"gradient", false}, {"gradient_alt", true, "more accurate; param2 is then 0..1"}});
  static inline const apex::ParamDecl<double> kDp =
      param::number("dp").range(1.0, 8.0).step(0.1).init(1.0).describe("image / accumulator resolution (gradient_alt: ~1.5)");
  static inline const apex::ParamDecl<double> kMinDist =
      param::number("min_dist").range(1.0, 10000.0).step(1.0).init(20.0).describe("pixels between centres");
  static inline const apex::ParamDecl<double> kParam1 =
      param::number("param1").range(1.0, 1000.0).step(1.0).init(100.0).describe("Canny's upper threshold (gradient_alt: ~300)");
  static inline const apex::ParamDecl<double> kParam2 =
      param::number("param2")
          .range(0.01, 1000.0)
          .step(0.01)
          .init(30.0)
          .describe("gradient: votes a centre needs; gradient_alt: how round, 0..1 (~0.9)");
  static inline const apex::ParamDecl<int> kMinRadius = param::integer("min_radius").range(0, 10000).step(1).describe("pixels");
  static inline const apex::ParamDecl<int> kMaxRadius =
      param::integer("max_radius").range(-1, 10000).step(1).describe("pixels; 0: no limit; -1 (gradient): centres only");
  static apex::Manifest manifest() {
    return apex::Manifest("Finds circles in a gray image (Hough transform, cv::HoughCircles)")
        .inCategory(kCategory)
        .input(kImage)
        .output(kCircles)
        .param(kMethod)
        .param(kDp)
        .param(kMinDist)
        .param(kParam1)
        .param(kParam2)
        .param(kMinRadius)
        .param(kMaxRadius);
  }
  void process() override {
    const Image& in = *image_.get();
    requireGray8(in);
    const bool alt = method_.get();  // gradient_alt
    if (alt && param2_.get() > 1)
      throw std::invalid_argument("gradient_alt takes param2 within 0..1 (how round a circle is), got " +
                                  std::to_string(param2_.get()));
    if (max_radius_.get() > 0 && min_radius_.get() > max_radius_.get())
      throw std::invalid_argument("min_radius " + std::to_string(min_radius_.get()) + " is above max_radius " +
                                  std::to_string(max_radius_.get()));
    auto out = std::make_shared<Circles>();
    out->header = in.header;
    out->image_size = in.mat.size();
    cv::HoughCircles(in.mat, out->circles, alt ? cv::HOUGH_GRADIENT_ALT : cv::HOUGH_GRADIENT, dp_.get(), min_dist_.get(),
                     param1_.get(), param2_.get(), min_radius_.get(), max_radius_.get());
    circles_.publish(std::move(out));
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Output<Circles> circles_{this, kCircles};
  apex::Choice<bool> method_{this, kMethod};
  apex::Param<double> dp_{this, kDp};
  apex::Param<double> min_dist_{this, kMinDist};
  apex::Param<double> param1_{this, kParam1};
  apex::Param<double> param2_{this, kParam2};
  apex::Param<int> min_radius_{this, kMinRadius};
  apex::Param<int> max_radius_{this, kMaxRadius};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::HoughLines, "apex_nodes/HoughLines");
APEX_REGISTER_NODE(apex_nodes::HoughCircles, "apex_nodes/HoughCircles");
