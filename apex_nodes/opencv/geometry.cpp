// Resize and Crop.
#include <opencv2/imgproc.hpp>

#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Resize : public ImageFilter {
 public:
  static inline const apex::ParamDecl<double> kScale = param::number("scale").range(0.01, 10.0).step(0.01).init(0.5);
  static inline const apex::ChoiceDecl<int> kInterpolation =
      param::choice<int>(
          "interpolation",
          {{"nearest", cv::INTER_NEAREST}, {"linear", cv::INTER_LINEAR}, {"area", cv::INTER_AREA}, {"cubic", cv::INTER_CUBIC}})
          .init("area");
  static apex::Manifest manifest() { return filterManifest("Scales an image").param(kScale).param(kInterpolation); }

 private:
  /** The scale keeps the size (scale 1, or close enough to round to it): cv::resize would copy. */
  bool passesThrough(const Image& in) const override {
    return cv::Size(cv::saturate_cast<int>(in.mat.cols * scale_.get()), cv::saturate_cast<int>(in.mat.rows * scale_.get())) ==
           in.mat.size();
  }
  void filter(const Image& in, Image& out) override {
    cv::resize(in.mat, out.mat, cv::Size(), scale_.get(), scale_.get(), interpolation_.get());
    if (out.mat.empty()) throw std::invalid_argument("scale " + std::to_string(scale_.get()) + " leaves no pixels");
  }
  apex::Param<double> scale_{this, kScale};
  apex::Choice<int> interpolation_{this, kInterpolation};
};

/** Not an ImageFilter: its output is a view of the input's pixels (no copy), kept alive by it. */
class Crop : public apex::Node {
 public:
  static inline const apex::ParamDecl<int> kX = param::integer("x").range(0, 100000).step(1);
  static inline const apex::ParamDecl<int> kY = param::integer("y").range(0, 100000).step(1);
  static inline const apex::ParamDecl<int> kWidth = param::integer("width").range(1, 100000).step(1).init(100000);
  static inline const apex::ParamDecl<int> kHeight = param::integer("height").range(1, 100000).step(1).init(100000);
  static apex::Manifest manifest() {
    return ImageFilter::filterManifest("Cuts out a rectangle (clipped to the image); shares the input's pixels")
        .param(kX)
        .param(kY)
        .param(kWidth)
        .param(kHeight);
  }
  void process() override {
    auto in = in_.get();
    requireImage(*in);
    const cv::Rect box = cv::Rect(x_.get(), y_.get(), width_.get(), height_.get()) & cv::Rect(0, 0, in->mat.cols, in->mat.rows);
    if (box.empty())
      throw std::invalid_argument("the crop lies outside the " + std::to_string(in->mat.cols) + "x" +
                                  std::to_string(in->mat.rows) + " image");
    auto out = std::make_shared<Image>(*in);
    out->mat = in->mat(box);  // no copy: a view, kept valid by `owner`
    out->owner = in;
    out_.publish(out);
  }

 private:
  apex::Input<Image> in_{this, ImageFilter::kImageIn};
  apex::Output<Image> out_{this, ImageFilter::kImageOut};
  apex::Param<int> x_{this, kX};
  apex::Param<int> y_{this, kY};
  apex::Param<int> width_{this, kWidth};
  apex::Param<int> height_{this, kHeight};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Resize, "apex_nodes/Resize");
APEX_REGISTER_NODE(apex_nodes::Crop, "apex_nodes/Crop");
