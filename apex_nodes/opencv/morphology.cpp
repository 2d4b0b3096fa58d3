// Morphology: erode, dilate, open, close with a rectangular, cross or elliptic kernel.
#include <opencv2/imgproc.hpp>

#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Morphology : public ImageFilter {
 public:
  static inline const apex::ParamDecl<std::string> kOperation =
      param::choice("operation", {"erode", "dilate", "open", "close"}).init("open");
  static inline const apex::ParamDecl<std::string> kShape =
      param::choice("shape", {"rect", "cross", "ellipse"}).describe("kernel shape");
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
    if (kernel_.empty()) {
      const auto& s = shape_.get();
      const int shape = s == "rect" ? cv::MORPH_RECT : s == "cross" ? cv::MORPH_CROSS : cv::MORPH_ELLIPSE;
      kernel_ = cv::getStructuringElement(shape, cv::Size(size_.get(), size_.get()));
    }
    const auto& op = operation_.get();
    const int code = op == "erode"    ? cv::MORPH_ERODE
                     : op == "dilate" ? cv::MORPH_DILATE
                     : op == "open"   ? cv::MORPH_OPEN
                                      : cv::MORPH_CLOSE;
    cv::morphologyEx(in.mat, out.mat, code, kernel_, cv::Point(-1, -1), iterations_.get());
  }
  apex::Param<std::string> operation_{this, kOperation};
  apex::Param<std::string> shape_{this, kShape};
  apex::Param<int> size_{this, kKernel};
  apex::Param<int> iterations_{this, kIterations};
  cv::Mat kernel_;  // rebuilt after a parameter change
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Morphology, "apex_nodes/Morphology");
