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
    const Image& in = *image_in_.get();
    requireImage(in);
    auto out = buffer_.next(in);
    const int k = kernel_size_.get();
    cv::GaussianBlur(in.mat, out->mat, cv::Size(k, k), sigma_.get());
    out->encoding = in.encoding;
    image_out_.publish(out);
  }

 private:
  apex::Input<Image> image_in_{this, "image"};
  apex::Output<Image> image_out_{this, "image"};
  apex::Param<int> kernel_size_{this, "kernel_size"};
  apex::Param<double> sigma_{this, "sigma"};
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
    const Image& in = *image_in_.get();
    requireImage(in, "1");
    static const std::map<std::string, int> kTypes{{"binary", cv::THRESH_BINARY}, {"binary_inv", cv::THRESH_BINARY_INV},
                                                   {"trunc", cv::THRESH_TRUNC}, {"tozero", cv::THRESH_TOZERO},
                                                   {"tozero_inv", cv::THRESH_TOZERO_INV}};
    int type = kTypes.at(type_.get());
    if (otsu_.get()) {
      if (in.mat.depth() != CV_8U) throw std::invalid_argument("Otsu needs an 8-bit image ('" + in.encoding + "')");
      type |= cv::THRESH_OTSU;
    }
    auto out = buffer_.next(in);
    cv::threshold(in.mat, out->mat, threshold_.get(), max_value_.get(), type);
    out->encoding = in.encoding;
    image_out_.publish(out);
  }

 private:
  apex::Input<Image> image_in_{this, "image"};
  apex::Output<Image> image_out_{this, "image"};
  apex::Param<double> threshold_{this, "threshold"};
  apex::Param<double> max_value_{this, "max_value"};
  apex::Param<std::string> type_{this, "type"};
  apex::Param<bool> otsu_{this, "otsu"};
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
    const Image& in = *image_.get();
    requireImage(in);
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image ('" + in.encoding + "')");
    auto out = buffer_.next(in);
    cv::Canny(in.mat, out->mat, threshold1_.get(), threshold2_.get(), std::stoi(aperture_.get()), l2_gradient_.get());
    out->encoding = "mono8";
    edges_.publish(out);
  }

 private:
  apex::Input<Image> image_{this, "image"};
  apex::Output<Image> edges_{this, "edges"};
  apex::Param<double> threshold1_{this, "threshold1"};
  apex::Param<double> threshold2_{this, "threshold2"};
  apex::Param<std::string> aperture_{this, "aperture"};
  apex::Param<bool> l2_gradient_{this, "l2_gradient"};
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::GaussianBlur, "apex_nodes/GaussianBlur");
APEX_REGISTER_NODE(apex_nodes::Threshold, "apex_nodes/Threshold");
APEX_REGISTER_NODE(apex_nodes::Canny, "apex_nodes/Canny");
