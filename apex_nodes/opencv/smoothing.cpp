// Smoothing filters: MedianBlur, BilateralFilter, BoxFilter.
#include <opencv2/imgproc.hpp>

#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class MedianBlur : public ImageFilter {
 public:
  static inline const apex::ParamDecl<int> kKsize =
      param::integer("ksize").range(1, 31).step(2).init(5).describe("aperture width and height, odd; above 5: 8-bit images only");
  static apex::Manifest manifest() {
    return filterManifest("Replaces each pixel by the median of its neighbourhood (removes salt-and-pepper noise)").param(kKsize);
  }

 private:
  void filter(const Image& in, Image& out) override {
    const int depth = in.mat.depth(), ksize = ksize_.get();
    if (depth != CV_8U && depth != CV_16U && depth != CV_32F)
      throw std::invalid_argument("cannot filter " + depthName(depth) + " pixels ('" + in.encoding + "'); needs 8U, 16U or 32F");
    if (ksize > 5 && depth != CV_8U)
      throw std::invalid_argument("ksize " + std::to_string(ksize) + " needs an 8-bit image, got " + depthName(depth) + " ('" +
                                  in.encoding + "'); ksize 3 or 5 takes 16U and 32F too");
    cv::medianBlur(in.mat, out.mat, ksize);
  }
  apex::Param<int> ksize_{this, kKsize};
};

class BilateralFilter : public ImageFilter {
 public:
  static inline const apex::ParamDecl<int> kD = param::integer("d").range(1, 25).step(1).init(9).describe(
      "diameter of each pixel's neighbourhood (5: real time, 9: offline)");
  static inline const apex::ParamDecl<double> kSigmaColor = param::number("sigma_color")
                                                                .range(0.0, 300.0)
                                                                .step(1.0)
                                                                .init(75.0)
                                                                .describe("how different colours may be and still be mixed");
  static inline const apex::ParamDecl<double> kSigmaSpace = param::number("sigma_space")
                                                                .range(0.0, 300.0)
                                                                .step(1.0)
                                                                .init(75.0)
                                                                .describe("how far apart pixels may be and still be mixed");
  static inline const apex::ChoiceDecl<int> kBorder =
      param::choice<int>("border_type", borderModes()).describe("how pixels beyond the edge are made up");
  static apex::Manifest manifest() {
    return filterManifest("Smooths an image but keeps its edges (8-bit or 32F, 1 or 3 channels)")
        .param(kD)
        .param(kSigmaColor)
        .param(kSigmaSpace)
        .param(kBorder);
  }
  BilateralFilter() : ImageFilter("13") {}

 private:
  void filter(const Image& in, Image& out) override {
    if (in.mat.depth() != CV_8U && in.mat.depth() != CV_32F)
      throw std::invalid_argument("cannot filter " + depthName(in.mat.depth()) + " pixels ('" + in.encoding +
                                  "'); needs 8U or 32F");
    cv::bilateralFilter(in.mat, out.mat, d_.get(), sigma_color_.get(), sigma_space_.get(), border_.get());
  }
  apex::Param<int> d_{this, kD};
  apex::Param<double> sigma_color_{this, kSigmaColor};
  apex::Param<double> sigma_space_{this, kSigmaSpace};
  apex::Choice<int> border_{this, kBorder};
};

class BoxFilter : public ImageFilter {
 public:
  static inline const apex::ParamDecl<int> kKsize =
      param::integer("ksize").range(1, 63).step(1).init(5).describe("kernel width and height in pixels");
  static inline const apex::ParamDecl<bool> kNormalize =
      param::flag("normalize")
          .init(true)
          .describe("on: the mean of the box; off: its sum (saturating at the pixel type's maximum)");
  static inline const apex::ChoiceDecl<int> kBorder =
      param::choice<int>("border_type", borderModes()).describe("how pixels beyond the edge are made up");
  static apex::Manifest manifest() {
    return filterManifest("Mean (or sum) of each pixel's box-shaped neighbourhood")
        .param(kKsize)
        .param(kNormalize)
        .param(kBorder);
  }
  BoxFilter() : ImageFilter("1234") {}

 private:
  void filter(const Image& in, Image& out) override {
    cv::boxFilter(in.mat, out.mat, -1, cv::Size(ksize_.get(), ksize_.get()), cv::Point(-1, -1), normalize_.get(), border_.get());
  }
  apex::Param<int> ksize_{this, kKsize};
  apex::Param<bool> normalize_{this, kNormalize};
  apex::Choice<int> border_{this, kBorder};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::MedianBlur, "apex_nodes/MedianBlur");
APEX_REGISTER_NODE(apex_nodes::BilateralFilter, "apex_nodes/BilateralFilter");
APEX_REGISTER_NODE(apex_nodes::BoxFilter, "apex_nodes/BoxFilter");
