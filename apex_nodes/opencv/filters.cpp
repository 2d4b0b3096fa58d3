// Small single-call filters: GaussianBlur, Threshold, Canny.
#include <map>
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {

class GaussianBlur : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Smooths an image with a Gaussian kernel")
        .input<Image>("image")
        .output<Image>("image")
        .param(apex::param::range("kernel_size", 1, 31, 2, 5).describe("odd"))
        .param(apex::param::range("sigma", 0.0, 50.0, 0.1, 0.0).describe("0: from the kernel size"));
  }
  void process() override {
    const Image& in = *input<Image>("image");
    requireImage(in);
    auto out = buffer_.next(in);
    const int k = param<int>("kernel_size");
    cv::GaussianBlur(in.mat, out->mat, cv::Size(k, k), param<double>("sigma"));
    out->encoding = in.encoding;
    publish<Image>("image", out);
  }

 private:
  OutputBuffer buffer_;
};

class Threshold : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Fixed-level threshold of a single-channel image (optionally Otsu)")
        .input<Image>("image")
        .output<Image>("image")
        .param(apex::param::range("threshold", 0.0, 255.0, 1.0, 128.0))
        .param(apex::param::range("max_value", 0.0, 255.0, 1.0, 255.0))
        .param(apex::param::options("type", {"binary", "binary_inv", "trunc", "tozero", "tozero_inv"}, "binary"))
        .param(apex::param::boolean("otsu", false).describe("choose the threshold from the histogram"));
  }
  void process() override {
    const Image& in = *input<Image>("image");
    requireImage(in, "1");
    static const std::map<std::string, int> kTypes{{"binary", cv::THRESH_BINARY}, {"binary_inv", cv::THRESH_BINARY_INV},
                                                   {"trunc", cv::THRESH_TRUNC}, {"tozero", cv::THRESH_TOZERO},
                                                   {"tozero_inv", cv::THRESH_TOZERO_INV}};
    int type = kTypes.at(param<std::string>("type"));
    if (param<bool>("otsu")) {
      if (in.mat.depth() != CV_8U) throw std::invalid_argument("Otsu needs an 8-bit image ('" + in.encoding + "')");
      type |= cv::THRESH_OTSU;
    }
    auto out = buffer_.next(in);
    cv::threshold(in.mat, out->mat, param<double>("threshold"), param<double>("max_value"), type);
    out->encoding = in.encoding;
    publish<Image>("image", out);
  }

 private:
  OutputBuffer buffer_;
};

class Canny : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Canny edge detector")
        .input<Image>("image", "8-bit")
        .output<Image>("edges", "mono8")
        .param(apex::param::range("threshold1", 0.0, 1000.0, 1.0, 50.0))
        .param(apex::param::range("threshold2", 0.0, 1000.0, 1.0, 150.0))
        .param(apex::param::options("aperture", {"3", "5", "7"}, "3"))
        .param(apex::param::boolean("l2_gradient", false));
  }
  void process() override {
    const Image& in = *input<Image>("image");
    requireImage(in);
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image ('" + in.encoding + "')");
    auto out = buffer_.next(in);
    cv::Canny(in.mat, out->mat, param<double>("threshold1"), param<double>("threshold2"),
              std::stoi(param<std::string>("aperture")), param<bool>("l2_gradient"));
    out->encoding = "mono8";
    publish<Image>("edges", out);
  }

 private:
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::GaussianBlur, "apex_nodes/GaussianBlur");
APEX_REGISTER_NODE(apex_nodes::Threshold, "apex_nodes/Threshold");
APEX_REGISTER_NODE(apex_nodes::Canny, "apex_nodes/Canny");
