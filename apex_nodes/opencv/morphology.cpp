// Morphology: erode, dilate, open, close with a rectangular, cross or elliptic kernel.
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {

class Morphology : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Morphological erode, dilate, open or close")
        .input<Image>("image")
        .output<Image>("image")
        .param(apex::param::options("operation", {"erode", "dilate", "open", "close"}, "open"))
        .param(apex::param::options("shape", {"rect", "cross", "ellipse"}, "rect").describe("kernel shape"))
        .param(apex::param::range("kernel_size", 1, 31, 2, 3).describe("kernel width and height, odd"))
        .param(apex::param::range("iterations", 1, 20, 1, 1));
  }
  void parameterChanged(const std::string&) override { kernel_.release(); }
  void process() override {
    const Image& in = *image_in_.get();
    requireImage(in);
    if (kernel_.empty()) {
      const auto& s = shape_.get();
      const int shape = s == "rect" ? cv::MORPH_RECT : s == "cross" ? cv::MORPH_CROSS : cv::MORPH_ELLIPSE;
      const int k = kernel_size_.get();
      kernel_ = cv::getStructuringElement(shape, cv::Size(k, k));
    }
    const auto& op = operation_.get();
    const int code = op == "erode" ? cv::MORPH_ERODE : op == "dilate" ? cv::MORPH_DILATE : op == "open" ? cv::MORPH_OPEN : cv::MORPH_CLOSE;
    auto out = buffer_.next(in);
    cv::morphologyEx(in.mat, out->mat, code, kernel_, cv::Point(-1, -1), iterations_.get());
    out->encoding = in.encoding;
    image_out_.publish(out);
  }

 private:
  apex::Input<Image> image_in_{this, "image"};
  apex::Output<Image> image_out_{this, "image"};
  apex::Param<std::string> operation_{this, "operation"};
  apex::Param<std::string> shape_{this, "shape"};
  apex::Param<int> kernel_size_{this, "kernel_size"};
  apex::Param<int> iterations_{this, "iterations"};
  cv::Mat kernel_;  // rebuilt after a parameter change
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Morphology, "apex_nodes/Morphology");
