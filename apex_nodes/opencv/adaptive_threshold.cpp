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
    const Image& in = *input<Image>("image");
    requireImage(in, "1");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image ('" + in.encoding + "')");
    auto out = buffer_.next(in);
    cv::adaptiveThreshold(in.mat, out->mat, param<double>("max_value"),
                          param<std::string>("method") == "mean" ? cv::ADAPTIVE_THRESH_MEAN_C : cv::ADAPTIVE_THRESH_GAUSSIAN_C,
                          param<std::string>("threshold_type") == "binary" ? cv::THRESH_BINARY : cv::THRESH_BINARY_INV,
                          param<int>("block_size"), param<double>("c"));
    out->encoding = "mono8";
    publish<Image>("image", out);
  }

 private:
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::AdaptiveThreshold, "apex_nodes/AdaptiveThreshold");
