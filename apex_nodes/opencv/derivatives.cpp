// Image derivatives: Sobel, Scharr, Laplacian, with a result depth of choice (16SC1, 32FC3...).
#include <opencv2/imgproc.hpp>

#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

constexpr int kSameDepth = -1;  // the ddepth choice's "same": the input's

/** Whether OpenCV's derivative filters take `src` pixels to `dst` ones. */
bool derivable(int src, int dst) {
  if (src == dst) return src == CV_8U || src == CV_16U || src == CV_16S || src == CV_32F || src == CV_64F;
  if (src == CV_8U) return dst == CV_16S || dst == CV_32F || dst == CV_64F;
  if (src == CV_16U || src == CV_16S) return dst == CV_32F || dst == CV_64F;
  return src == CV_32F && dst == CV_64F;
}

const apex::ParamDecl<double> kScale =
    param::number("scale").range(-100.0, 100.0).step(0.01).init(1.0).describe("factor on the derivatives");
const apex::ParamDecl<double> kDelta =
    param::number("delta").range(-1000.0, 1000.0).step(0.1).init(0.0).describe("added to the derivatives after scaling");
const apex::ChoiceDecl<int> kDdepth =
    param::choice<int>("ddepth", {{"16S", CV_16S}, {"32F", CV_32F}, {"64F", CV_64F}, {"same", kSameDepth}})
        .describe("the result's depth: 16S for 8-bit images; same: saturates at the input's range");
const apex::ChoiceDecl<int> kBorder =
    param::choice<int>("border_type", borderModes()).describe("how pixels beyond the edge are made up");

/** The depth a `ddepth` choice gives for pixels of depth `src`. */
int depthFrom(int ddepth, int src) { return ddepth == kSameDepth ? src : ddepth; }

/** The depth the `ddepth` choice (named `name`) gives for `in`; an error naming both if OpenCV
 *  cannot make it. */
int resultDepth(const Image& in, int ddepth, const std::string& name) {
  const int src = in.mat.depth(), dst = depthFrom(ddepth, src);
  if (derivable(src, dst)) return dst;
  std::vector<std::string> choices;
  for (const auto& option : kDdepth.options())
    if (derivable(src, depthFrom(option.value, src))) choices.push_back(option.name);
  if (choices.empty())  // not even "same": OpenCV filters no such pixels
    throw std::invalid_argument("cannot differentiate " + depthName(src) + " pixels ('" + in.encoding +
                                "'); needs 8U, 16U, 16S, 32F or 64F");
  std::string words;
  for (std::size_t i = 0; i < choices.size(); ++i) words += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
  throw std::invalid_argument("ddepth " + name + " cannot hold the derivatives of a " + depthName(src) + " image ('" +
                              in.encoding + "'); choose " + words);
}

}  // namespace

/** What the three share: scale, delta, ddepth, border_type. */
class DerivativeFilter : public ImageFilter {
 public:
  static apex::Manifest derivativeManifest(std::string description) {
    return filterManifest(std::move(description)).param(kScale).param(kDelta).param(kDdepth).param(kBorder);
  }

 protected:
  DerivativeFilter() : ImageFilter("134") {}
  /** The result's depth for `in`, and its encoding in `out`. */
  int depthFor(const Image& in, Image& out) const {
    const int depth = resultDepth(in, ddepth_.get(), ddepth_.text());
    out.encoding = encodingOf(in, in.mat.channels(), depth);
    return depth;
  }
  apex::Param<double> scale_{this, kScale};
  apex::Param<double> delta_{this, kDelta};
  apex::Choice<int> ddepth_{this, kDdepth};
  apex::Choice<int> border_{this, kBorder};
};

class Sobel : public DerivativeFilter {
 public:
  static inline const apex::ParamDecl<int> kDx =
      param::integer("dx").range(0, 2).step(1).init(1).describe("order of the x derivative");
  static inline const apex::ParamDecl<int> kDy = param::integer("dy").range(0, 2).step(1).describe("order of the y derivative");
  static inline const apex::ParamDecl<int> kKsize =
      param::integer("ksize").range(1, 7).step(2).init(3).describe("kernel size, odd; 1: 3x1 or 1x3 without smoothing");
  static apex::Manifest manifest() {
    return derivativeManifest("First or second image derivatives with the Sobel operator").param(kDx).param(kDy).param(kKsize);
  }

 private:
  void filter(const Image& in, Image& out) override {
    if (dx_.get() == 0 && dy_.get() == 0) throw std::invalid_argument("dx and dy are both 0: there is no derivative to take");
    const int depth = depthFor(in, out);
    cv::Sobel(in.mat, out.mat, depth, dx_.get(), dy_.get(), ksize_.get(), scale_.get(), delta_.get(), border_.get());
  }
  apex::Param<int> dx_{this, kDx};
  apex::Param<int> dy_{this, kDy};
  apex::Param<int> ksize_{this, kKsize};
};

class Scharr : public DerivativeFilter {
 public:
  static inline const apex::ParamDecl<int> kDx = param::integer("dx").range(0, 1).step(1).init(1).describe("1: the x derivative");
  static inline const apex::ParamDecl<int> kDy = param::integer("dy").range(0, 1).step(1).describe("1: the y derivative");
  static apex::Manifest manifest() {
    return derivativeManifest("First x or y image derivative with the 3x3 Scharr kernel (more accurate than Sobel's)")
        .param(kDx)
        .param(kDy);
  }

 private:
  void filter(const Image& in, Image& out) override {
    if (dx_.get() + dy_.get() != 1)
      throw std::invalid_argument("Scharr takes one first derivative: dx = 1 or dy = 1, not dx = " + std::to_string(dx_.get()) +
                                  ", dy = " + std::to_string(dy_.get()));
    const int depth = depthFor(in, out);
    cv::Scharr(in.mat, out.mat, depth, dx_.get(), dy_.get(), scale_.get(), delta_.get(), border_.get());
  }
  apex::Param<int> dx_{this, kDx};
  apex::Param<int> dy_{this, kDy};
};

class Laplacian : public DerivativeFilter {
 public:
  static inline const apex::ParamDecl<int> kKsize = param::integer("ksize").range(1, 31).step(2).init(1).describe(
      "aperture of the second-derivative filters, odd; 1: the 3x3 kernel [0 1 0; 1 -4 1; 0 1 0]");
  static apex::Manifest manifest() {
    return derivativeManifest("Laplacian of an image: the sum of its second x and y derivatives").param(kKsize);
  }

 private:
  void filter(const Image& in, Image& out) override {
    const int depth = depthFor(in, out);
    cv::Laplacian(in.mat, out.mat, depth, ksize_.get(), scale_.get(), delta_.get(), border_.get());
  }
  apex::Param<int> ksize_{this, kKsize};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Sobel, "apex_nodes/Sobel");
APEX_REGISTER_NODE(apex_nodes::Scharr, "apex_nodes/Scharr");
APEX_REGISTER_NODE(apex_nodes::Laplacian, "apex_nodes/Laplacian");
