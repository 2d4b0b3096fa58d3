// Intensity transforms: EqualizeHist, CLAHE, Normalize, ConvertScale.
#include <cfloat>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

namespace {
constexpr int kSameDepth = -1;  // a depth choice's "same": the input's
}  // namespace

class EqualizeHist : public ImageFilter {
 public:
  static apex::Manifest manifest() {
    return filterManifest("Spreads a gray image's histogram over the whole range, for contrast (8-bit, single channel)");
  }
  EqualizeHist() : ImageFilter("1", true) {}

 private:
  void filter(const Image& in, Image& out) override { cv::equalizeHist(in.mat, out.mat); }
};

class CLAHE : public ImageFilter {
 public:
  static inline const apex::ParamDecl<double> kClipLimit =
      param::number("clip_limit")
          .range(0.0, 100.0)
          .step(0.1)
          .init(2.0)
          .describe("contrast limit per tile, in multiples of a flat histogram; 0: no limit");
  static inline const apex::ParamDecl<int> kTileGridSize =
      param::integer("tile_grid_size").range(1, 64).step(1).init(8).describe("tiles across and down, each equalized on its own");
  static apex::Manifest manifest() {
    return filterManifest("Contrast-limited adaptive histogram equalization (8- or 16-bit, single channel)")
        .param(kClipLimit)
        .param(kTileGridSize);
  }
  CLAHE() : ImageFilter("1") {}

 private:
  void filter(const Image& in, Image& out) override {
    if (in.mat.depth() != CV_8U && in.mat.depth() != CV_16U)
      throw std::invalid_argument("needs an 8- or 16-bit image, got " + depthName(in.mat.depth()) + " ('" + in.encoding + "')");
    clahe_->setClipLimit(clip_limit_.get());
    clahe_->setTilesGridSize(cv::Size(tile_grid_size_.get(), tile_grid_size_.get()));
    clahe_->apply(in.mat, out.mat);
  }
  apex::Param<double> clip_limit_{this, kClipLimit};
  apex::Param<int> tile_grid_size_{this, kTileGridSize};
  cv::Ptr<cv::CLAHE> clahe_ = cv::createCLAHE();
};

class Normalize : public ImageFilter {
 public:
  static inline const apex::ParamDecl<double> kAlpha =
      param::number("alpha")
          .range(-65535.0, 65535.0)
          .step(0.01)
          .init(0.0)
          .describe("minmax: the lowest value of the result; else the norm it gets");
  static inline const apex::ParamDecl<double> kBeta =
      param::number("beta").range(-65535.0, 65535.0).step(0.01).init(255.0).describe("minmax: the highest value of the result");
  static inline const apex::ChoiceDecl<int> kNormType =
      param::choice<int>("norm_type",
                         {{"minmax", cv::NORM_MINMAX}, {"inf", cv::NORM_INF}, {"l1", cv::NORM_L1}, {"l2", cv::NORM_L2}})
          .describe(
              "minmax: stretch to [alpha, beta]; else "
              "scale so that this norm is alpha");
  static inline const apex::ChoiceDecl<int> kDtype =
      param::choice<int>("dtype", {{"same", kSameDepth}, {"8U", CV_8U}, {"16U", CV_16U}, {"32F", CV_32F}, {"64F", CV_64F}})
          .describe("the result's depth");
  static apex::Manifest manifest() {
    return filterManifest("Scales an image's values to a range or to a norm (cv::normalize)")
        .param(kAlpha)
        .param(kBeta)
        .param(kNormType)
        .param(kDtype);
  }

 private:
  void filter(const Image& in, Image& out) override {
    const int depth = dtype_.get() == kSameDepth ? in.mat.depth() : dtype_.get();
    cv::normalize(in.mat, out.mat, alpha_.get(), beta_.get(), norm_type_.get(), depth);
    out.encoding = encodingOf(in, in.mat.channels(), depth);
  }
  apex::Param<double> alpha_{this, kAlpha};
  apex::Param<double> beta_{this, kBeta};
  apex::Choice<int> norm_type_{this, kNormType};
  apex::Choice<int> dtype_{this, kDtype};
};

class ConvertScale : public ImageFilter {
 public:
  static inline const apex::ParamDecl<double> kAlpha =
      param::number("alpha").range(-1000.0, 1000.0).step(0.001).init(1.0).describe("factor on each value");
  static inline const apex::ParamDecl<double> kBeta =
      param::number("beta").range(-65535.0, 65535.0).step(0.01).init(0.0).describe("added after scaling");
  static inline const apex::ChoiceDecl<int> kRtype =
      param::choice<int>("rtype", {{"8U", CV_8U}, {"16U", CV_16U}, {"32F", CV_32F}, {"same", kSameDepth}})
          .describe("the result's depth (values saturate at its range)");
  static apex::Manifest manifest() {
    return filterManifest("Scales and shifts each value, alpha * x + beta, into a depth of choice (cv::Mat::convertTo)")
        .param(kAlpha)
        .param(kBeta)
        .param(kRtype);
  }

 private:
  /** alpha 1, beta 0 (to DBL_EPSILON, as cv::Mat::convertTo tells), the same depth: a copy. */
  bool passesThrough(const Image& in) const override {
    return std::abs(alpha_.get() - 1) < DBL_EPSILON && std::abs(beta_.get()) < DBL_EPSILON && depth(in) == in.mat.depth();
  }
  void filter(const Image& in, Image& out) override {
    in.mat.convertTo(out.mat, depth(in), alpha_.get(), beta_.get());
    out.encoding = encodingOf(in, in.mat.channels(), depth(in));
  }
  apex::Param<double> alpha_{this, kAlpha};
  apex::Param<double> beta_{this, kBeta};
  int depth(const Image& in) const { return rtype_.get() == kSameDepth ? in.mat.depth() : rtype_.get(); }
  apex::Choice<int> rtype_{this, kRtype};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::EqualizeHist, "apex_nodes/EqualizeHist");
APEX_REGISTER_NODE(apex_nodes::CLAHE, "apex_nodes/CLAHE");
APEX_REGISTER_NODE(apex_nodes::Normalize, "apex_nodes/Normalize");
APEX_REGISTER_NODE(apex_nodes::ConvertScale, "apex_nodes/ConvertScale");
