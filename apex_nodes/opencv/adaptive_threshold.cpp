// AdaptiveThreshold: the paper's Fig. 3 parameters, on a single-channel 8-bit image.
#include <opencv2/imgproc.hpp>

#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class AdaptiveThreshold : public ImageFilter {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "single-channel 8-bit"};
  static inline const apex::OutputPort<Image> kBinary{"image", "binary (0 or max_value)"};
  static inline const apex::ParamDecl<double> kMaxValue =
      param::number("max_value").range(0.0, 255.0).step(1.0).init(255.0).describe("value of pixels that pass");
  static inline const apex::ChoiceDecl<int> kMethod =
      param::choice<int>("method", {{"mean", cv::ADAPTIVE_THRESH_MEAN_C}, {"gaussian", cv::ADAPTIVE_THRESH_GAUSSIAN_C}})
          .describe("how the neighbourhood is weighted");
  static inline const apex::ChoiceDecl<int> kType =
      param::choice<int>("threshold_type", {{"binary", cv::THRESH_BINARY}, {"binary_inv", cv::THRESH_BINARY_INV}});
  static inline const apex::ParamDecl<int> kBlock =
      param::integer("block_size").range(3, 101).step(2).init(11).describe("neighbourhood size, odd");
  static inline const apex::ParamDecl<double> kC =
      param::number("c").range(-100.0, 100.0).step(0.5).init(2.0).describe("subtracted from the mean");
  static apex::Manifest manifest() {
    return filterManifest("Thresholds each pixel against the mean or Gaussian-weighted mean of its neighbourhood", kImage,
                          kBinary)
        .param(kMaxValue)
        .param(kMethod)
        .param(kType)
        .param(kBlock)
        .param(kC);
  }
  AdaptiveThreshold() : ImageFilter("1", true, kImage, kBinary) {}

 private:
  void filter(const Image& in, Image& out) override {
    cv::adaptiveThreshold(in.mat, out.mat, max_value_.get(), method_.get(), type_.get(), block_.get(), c_.get());
    out.encoding = "mono8";
  }
  apex::Param<double> max_value_{this, kMaxValue};
  apex::Choice<int> method_{this, kMethod};
  apex::Choice<int> type_{this, kType};
  apex::Param<int> block_{this, kBlock};
  apex::Param<double> c_{this, kC};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::AdaptiveThreshold, "apex_nodes/AdaptiveThreshold");
