// Resize and Crop.
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {

class Resize : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Scales an image")
        .input<Image>("image")
        .output<Image>("image")
        .param(apex::param::range("scale", 0.01, 10.0, 0.01, 0.5))
        .param(apex::param::options("interpolation", {"nearest", "linear", "area", "cubic"}, "area"));
  }
  void process() override {
    const Image& in = *image_in_.get();
    requireImage(in);
    const auto& i = interpolation_.get();
    const int interp = i == "nearest" ? cv::INTER_NEAREST : i == "linear" ? cv::INTER_LINEAR : i == "area" ? cv::INTER_AREA : cv::INTER_CUBIC;
    const double s = scale_.get();
    auto out = buffer_.next(in);
    cv::resize(in.mat, out->mat, cv::Size(), s, s, interp);
    if (out->mat.empty()) throw std::invalid_argument("scale " + std::to_string(s) + " leaves no pixels");
    out->encoding = in.encoding;
    image_out_.publish(out);
  }

 private:
  apex::Input<Image> image_in_{this, "image"};
  apex::Output<Image> image_out_{this, "image"};
  apex::Param<double> scale_{this, "scale"};
  apex::Param<std::string> interpolation_{this, "interpolation"};
  OutputBuffer buffer_;
};

class Crop : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Cuts out a rectangle (clipped to the image); shares the input's pixels")
        .input<Image>("image")
        .output<Image>("image")
        .param(apex::param::range("x", 0, 100000, 1, 0))
        .param(apex::param::range("y", 0, 100000, 1, 0))
        .param(apex::param::range("width", 1, 100000, 1, 100000))
        .param(apex::param::range("height", 1, 100000, 1, 100000));
  }
  void process() override {
    auto in = image_in_.get();
    requireImage(*in);
    const cv::Rect want(x_.get(), y_.get(), width_.get(), height_.get());
    const cv::Rect box = want & cv::Rect(0, 0, in->mat.cols, in->mat.rows);
    if (box.empty()) throw std::invalid_argument("the crop lies outside the " + std::to_string(in->mat.cols) + "x" +
                                                 std::to_string(in->mat.rows) + " image");
    auto out = std::make_shared<Image>(*in);
    out->mat = in->mat(box);  // no copy: a view, kept valid by `owner`
    out->owner = in;
    image_out_.publish(out);
  }

 private:
  apex::Input<Image> image_in_{this, "image"};
  apex::Output<Image> image_out_{this, "image"};
  apex::Param<int> x_{this, "x"};
  apex::Param<int> y_{this, "y"};
  apex::Param<int> width_{this, "width"};
  apex::Param<int> height_{this, "height"};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Resize, "apex_nodes/Resize");
APEX_REGISTER_NODE(apex_nodes::Crop, "apex_nodes/Crop");
