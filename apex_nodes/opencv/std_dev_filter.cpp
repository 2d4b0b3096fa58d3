// StdDevFilter: the standard deviation of each pixel's neighbourhood (MATLAB's stdfilt): near 0 on
// flat areas (a painted sign, a wall), high on texture and edges. Thresholded, it finds regions
// of even colour that an intensity threshold alone would join to their darker surroundings.
#include <opencv2/imgproc.hpp>

#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class StdDevFilter : public ImageFilter {
 public:
  static inline const apex::ParamDecl<int> kKsize =
      param::integer("ksize").range(3, 63).step(2).init(5).describe("neighbourhood width and height in pixels, odd");
  static inline const apex::ParamDecl<double> kScale =
      param::number("scale")
          .range(0.01, 100.0)
          .step(0.01)
          .init(1.0)
          .describe("the result is the deviation times this, in the input's pixel type (8-bit: rounded, at most 255)");
  static inline const apex::ChoiceDecl<int> kBorder =
      param::choice<int>("border_type", borderModes()).describe("how pixels beyond the edge are made up");
  static apex::Manifest manifest() {
    return filterManifest(
               "Standard deviation of each pixel's neighbourhood (as MATLAB's stdfilt): low on flat areas, high on "
               "texture and edges")
        .param(kKsize)
        .param(kScale)
        .param(kBorder);
  }
  StdDevFilter() : ImageFilter("1") {}

 private:
  void filter(const Image& in, Image& out) override {
    const int depth = in.mat.depth();
    if (depth != CV_8U && depth != CV_16U && depth != CV_32F)
      throw std::invalid_argument("cannot filter " + depthName(depth) + " pixels ('" + in.encoding + "'); needs 8U, 16U or 32F");
    const cv::Size k(ksize_.get(), ksize_.get());
    const int border = border_.get();
    in.mat.convertTo(value_, CV_64F);  // doubles: E[x²] - E[x]² in floats loses a flat area's small deviations
    cv::multiply(value_, value_, square_);
    cv::boxFilter(value_, mean_, CV_64F, k, cv::Point(-1, -1), true, border);  // E[x]
    cv::boxFilter(square_, square_, CV_64F, k, cv::Point(-1, -1), true, border);  // E[x²]
    cv::multiply(mean_, mean_, mean_);
    cv::subtract(square_, mean_, square_);
    cv::max(square_, 0.0, square_);  // rounding can make a flat area's variance a hair below 0
    cv::sqrt(square_, square_);
    square_.convertTo(out.mat, depth, scale_.get());
  }
  apex::Param<int> ksize_{this, kKsize};
  apex::Param<double> scale_{this, kScale};
  apex::Choice<int> border_{this, kBorder};
  cv::Mat value_, square_, mean_;  // kept between frames: no allocation per frame
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::StdDevFilter, "apex_nodes/StdDevFilter");
