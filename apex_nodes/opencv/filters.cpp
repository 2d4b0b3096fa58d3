// Small single-call filters: GaussianBlur, Threshold, Canny.
#include <opencv2/imgproc.hpp>

#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class GaussianBlur : public ImageFilter {
 public:
  static inline const apex::ParamDecl<int> kKernel = param::integer("kernel_size").range(1, 31).step(2).init(5).describe("odd");
  static inline const apex::ParamDecl<double> kSigma =
      param::number("sigma").range(0.0, 50.0).step(0.1).describe("0: from the kernel size");
  static apex::Manifest manifest() {
    return filterManifest("Smooths an image with a Gaussian kernel").param(kKernel).param(kSigma);
  }

 private:
  void filter(const Image& in, Image& out) override {
    cv::GaussianBlur(in.mat, out.mat, cv::Size(kernel_.get(), kernel_.get()), sigma_.get());
  }
  apex::Param<int> kernel_{this, kKernel};
  apex::Param<double> sigma_{this, kSigma};
};

class Threshold : public ImageFilter {
 public:
  static inline const apex::ParamDecl<double> kThreshold = param::number("threshold").range(0.0, 255.0).step(1.0).init(128.0);
  static inline const apex::ParamDecl<double> kMaxValue = param::number("max_value").range(0.0, 255.0).step(1.0).init(255.0);
  static inline const apex::ChoiceDecl<int> kType = param::choice<int>("type", {{"binary", cv::THRESH_BINARY},
                                                                                {"binary_inv", cv::THRESH_BINARY_INV},
                                                                                {"trunc", cv::THRESH_TRUNC},
                                                                                {"tozero", cv::THRESH_TOZERO},
                                                                                {"tozero_inv", cv::THRESH_TOZERO_INV}});
  static inline const apex::ParamDecl<bool> kOtsu = param::flag("otsu").describe("choose the threshold from the histogram");
  static apex::Manifest manifest() {
    return filterManifest("Fixed-level threshold of a single-channel image (optionally Otsu)")
        .param(kThreshold)
        .param(kMaxValue)
        .param(kType)
        .param(kOtsu);
  }
  Threshold() : ImageFilter("1") {}

 private:
  void filter(const Image& in, Image& out) override {
    int type = type_.get();
    if (otsu_.get()) {
      if (in.mat.depth() != CV_8U) throw std::invalid_argument("Otsu needs an 8-bit image ('" + in.encoding + "')");
      type |= cv::THRESH_OTSU;
    }
    cv::threshold(in.mat, out.mat, threshold_.get(), max_value_.get(), type);
  }
  apex::Param<double> threshold_{this, kThreshold};
  apex::Param<double> max_value_{this, kMaxValue};
  apex::Choice<int> type_{this, kType};
  apex::Param<bool> otsu_{this, kOtsu};
};

class Canny : public ImageFilter {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit"};
  static inline const apex::OutputPort<Image> kEdges{"edges", "mono8"};
  static inline const apex::ParamDecl<double> kLow = param::number("threshold1").range(0.0, 1000.0).step(1.0).init(50.0);
  static inline const apex::ParamDecl<double> kHigh = param::number("threshold2").range(0.0, 1000.0).step(1.0).init(150.0);
  static inline const apex::ChoiceDecl<int> kAperture = param::choice<int>("aperture", {{"3", 3}, {"5", 5}, {"7", 7}});
  static inline const apex::ParamDecl<bool> kL2 = param::flag("l2_gradient");
  static apex::Manifest manifest() {
    return filterManifest("Canny edge detector", kImage, kEdges).param(kLow).param(kHigh).param(kAperture).param(kL2);
  }
  Canny() : ImageFilter("134", true, kImage, kEdges) {}

 private:
  void filter(const Image& in, Image& out) override {
    cv::Canny(in.mat, out.mat, low_.get(), high_.get(), aperture_.get(), l2_.get());
    out.encoding = "mono8";
  }
  apex::Param<double> low_{this, kLow};
  apex::Param<double> high_{this, kHigh};
  apex::Choice<int> aperture_{this, kAperture};
  apex::Param<bool> l2_{this, kL2};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::GaussianBlur, "apex_nodes/GaussianBlur");
APEX_REGISTER_NODE(apex_nodes::Threshold, "apex_nodes/Threshold");
APEX_REGISTER_NODE(apex_nodes::Canny, "apex_nodes/Canny");
