// AdaptiveThreshold: the paper's Fig. 3 parameters, on a single-channel 8-bit image.
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {

class AdaptiveThreshold : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Thresholds each pixel against the mean or Gaussian-weighted mean of its neighbourhood")
        .input<Image>("image", "single-channel 8-bit")
        .output<Image>("image", "binary (0 or max_value)")
        .param(apex::param::range("max_value", 0.0, 255.0, 1.0, 255.0).describe("value of pixels that pass"))
        .param(apex::param::options("method", {"mean", "gaussian"}, "mean").describe("how the neighbourhood is weighted"))
        .param(apex::param::options("threshold_type", {"binary", "binary_inv"}, "binary"))
        .param(apex::param::range("block_size", 3, 101, 2, 11).describe("neighbourhood size, odd"))
        .param(apex::param::range("c", -100.0, 100.0, 0.5, 2.0).describe("subtracted from the mean"));
  }
  void process() override {
    const Image& in = *image_in_.get();
    requireImage(in, "1");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image ('" + in.encoding + "')");
    auto out = buffer_.next(in);
    cv::adaptiveThreshold(in.mat, out->mat, max_value_.get(),
                          method_.get() == "mean" ? cv::ADAPTIVE_THRESH_MEAN_C : cv::ADAPTIVE_THRESH_GAUSSIAN_C,
                          threshold_type_.get() == "binary" ? cv::THRESH_BINARY : cv::THRESH_BINARY_INV,
                          block_size_.get(), c_.get());
    out->encoding = "mono8";
    image_out_.publish(out);
  }

 private:
  apex::Input<Image> image_in_{this, "image"};
  apex::Output<Image> image_out_{this, "image"};
  apex::Param<double> max_value_{this, "max_value"};
  apex::Param<std::string> method_{this, "method"};
  apex::Param<std::string> threshold_type_{this, "threshold_type"};
  apex::Param<int> block_size_{this, "block_size"};
  apex::Param<double> c_{this, "c"};
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::AdaptiveThreshold, "apex_nodes/AdaptiveThreshold");
