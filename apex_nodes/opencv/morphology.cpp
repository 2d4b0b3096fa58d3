// Morphology: erode, dilate, open, close with a rectangular, cross or elliptic kernel.
#include <opencv2/imgproc.hpp>

#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Morphology : public ImageFilter {
 public:
  static inline const apex::ChoiceDecl<int> kOperation =
      param::choice<int>(
          "operation",
          {{"erode", cv::MORPH_ERODE}, {"dilate", cv::MORPH_DILATE}, {"open", cv::MORPH_OPEN}, {"close", cv::MORPH_CLOSE}})
          .init("open");
  static inline const apex::ChoiceDecl<int> kShape =
      param::choice<int>("shape", {{"rect", cv::MORPH_RECT}, {"cross", cv::MORPH_CROSS}, {"ellipse", cv::MORPH_ELLIPSE}})
          .describe("kernel shape");
  static inline const apex::ParamDecl<int> kKernel =
      param::integer("kernel_size").range(1, 31).step(2).init(3).describe("kernel width and height, odd");
  static inline const apex::ParamDecl<int> kIterations = param::integer("iterations").range(1, 20).step(1);
  static apex::Manifest manifest() {
    return filterManifest("Morphological erode, dilate, open or close")
        .param(kOperation)
        .param(kShape)
        .param(kKernel)
        .param(kIterations);
  }
  void parameterChanged(const std::string&) override { kernel_.release(); }

 private:
  void filter(const Image& in, Image& out) override {
    if (kernel_.empty()) kernel_ = cv::getStructuringElement(shape_.get(), cv::Size(size_.get(), size_.get()));
    cv::morphologyEx(in.mat, out.mat, operation_.get(), kernel_, cv::Point(-1, -1), iterations_.get());
  }
  apex::Choice<int> operation_{this, kOperation};
  apex::Choice<int> shape_{this, kShape};
  apex::Param<int> size_{this, kKernel};
  apex::Param<int> iterations_{this, kIterations};
  cv::Mat kernel_;  // rebuilt after a parameter change
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Morphology, "apex_nodes/Morphology");
