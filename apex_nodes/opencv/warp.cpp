// Geometry and distance: Flip, PyrDown, PyrUp, WarpPerspective, DistanceTransform.
#include <opencv2/imgproc.hpp>

#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Flip : public ImageFilter {
 public:
  static inline const apex::ChoiceDecl<int> kFlipCode =
      param::choice<int>("flip_code", {{"horizontal", 1, "mirror left-right (flipCode 1)"},
                                       {"vertical", 0, "upside down (0)"},
                                       {"both", -1, "turn by 180 degrees (-1)"}});
  static apex::Manifest manifest() {
    return filterManifest("Mirrors an image left-right, upside down, or both").param(kFlipCode);
  }
  Flip() : ImageFilter("1234") {}

 private:
  void filter(const Image& in, Image& out) override { cv::flip(in.mat, out.mat, flip_code_.get()); }
  apex::Choice<int> flip_code_{this, kFlipCode};
};

class PyrDown : public ImageFilter {
 public:
  static apex::Manifest manifest() {
    return filterManifest("Blurs an image and halves its size, (w + 1) / 2 by (h + 1) / 2: one step down a Gaussian pyramid");
  }
  PyrDown() : ImageFilter("1234") {}

 private:
  void filter(const Image& in, Image& out) override { cv::pyrDown(in.mat, out.mat); }
};

class PyrUp : public ImageFilter {
 public:
  static apex::Manifest manifest() {
    return filterManifest("Doubles an image's size and smooths it: one step up a Gaussian pyramid");
  }
  PyrUp() : ImageFilter("1234") {}

 private:
  void filter(const Image& in, Image& out) override { cv::pyrUp(in.mat, out.mat); }
};

class WarpPerspective : public ImageFilter {
 public:
  static inline const apex::ParamDecl<std::vector<double>> kM =
      param::list("m")
          .init({1, 0, 0, 0, 1, 0, 0, 0, 1})
          .describe("the 3x3 perspective transform M, row by row, from input to result pixels");
  static inline const apex::ParamDecl<int> kWidth =
      param::integer("width").range(0, 8192).step(1).describe("dsize: the result's width in pixels; 0: the input's");
  static inline const apex::ParamDecl<int> kHeight =
      param::integer("height").range(0, 8192).step(1).describe("dsize: the result's height in pixels; 0: the input's");
  static inline const apex::ChoiceDecl<int> kInterpolation =
      param::choice<int>("interpolation", {{"linear", cv::INTER_LINEAR},
                                           {"nearest", cv::INTER_NEAREST},
                                           {"cubic", cv::INTER_CUBIC},
                                           {"lanczos4", cv::INTER_LANCZOS4}});
  static inline const apex::ParamDecl<bool> kInverse =
      param::flag("inverse_map").describe("m maps result pixels to input pixels (WARP_INVERSE_MAP)");
  static inline const apex::ChoiceDecl<int> kBorder =
      param::choice<int>("border_mode", borderModes())
          .init("constant")
          .describe("how pixels from beyond the edge are made up; constant: black");
  static apex::Manifest manifest() {
    return filterManifest(
               "Warps an image by the 3x3 perspective transform m (a parameter; a matrix input comes with FindHomography)")
        .param(kM)
        .param(kWidth)
        .param(kHeight)
        .param(kInterpolation)
        .param(kInverse)
        .param(kBorder);
  }
  WarpPerspective() : ImageFilter("1234") {}

 private:
  /** m is the identity and the size the input's: every pixel lands on itself, weighted 1 (its
   *  neighbours 0), so the warp is a copy; but not where OpenCV would refuse the depth, nor for a
   *  float image with NaN or infinite values, which the zero weights spread to their neighbours
   *  (0 * NaN is NaN) except with nearest. */
  bool passesThrough(const Image& in) const override {
    static const std::vector<double> kIdentity{1, 0, 0, 0, 1, 0, 0, 0, 1};
    if (m_.get() != kIdentity) return false;
    if ((width_.get() > 0 && width_.get() != in.mat.cols) || (height_.get() > 0 && height_.get() != in.mat.rows)) return false;
    const int depth = in.mat.depth();
    if (interpolation_.get() == cv::INTER_NEAREST) return depth != CV_16F;
    if (depth == CV_8U || depth == CV_16U || depth == CV_16S) return true;
    return (depth == CV_32F || depth == CV_64F) && cv::checkRange(in.mat);
  }
  void filter(const Image& in, Image& out) override {
    const std::vector<double>& m = m_.get();
    if (m.size() != 9)
      throw std::invalid_argument("'m' takes nine numbers (the 3x3 matrix, row by row), not " + std::to_string(m.size()));
    const cv::Matx33d matrix(m.data());
    if (!inverse_.get() && cv::determinant(matrix) == 0)
      throw std::invalid_argument("the matrix m is singular: it maps the image onto a line or a point");
    int flags = interpolation_.get();
    if (inverse_.get()) flags |= cv::WARP_INVERSE_MAP;
    const cv::Size size(width_.get() > 0 ? width_.get() : in.mat.cols, height_.get() > 0 ? height_.get() : in.mat.rows);
    cv::warpPerspective(in.mat, out.mat, matrix, size, flags, border_.get());
  }
  apex::Param<std::vector<double>> m_{this, kM};
  apex::Param<int> width_{this, kWidth};
  apex::Param<int> height_{this, kHeight};
  apex::Choice<int> interpolation_{this, kInterpolation};
  apex::Param<bool> inverse_{this, kInverse};
  apex::Choice<int> border_{this, kBorder};
};

class DistanceTransform : public ImageFilter {
 public:
  static inline const apex::OutputPort<Image> kDistances{"image", "32FC1: each pixel's distance to the nearest zero pixel"};
  static inline const apex::ChoiceDecl<int> kDistanceType = param::choice<int>(
      "distance_type", {{"l2", cv::DIST_L2, "Euclidean"}, {"l1", cv::DIST_L1, "city block"}, {"c", cv::DIST_C, "chessboard"}});
  static inline const apex::ChoiceDecl<int> kMaskSize =
      param::choice<int>("mask_size", {{"3", cv::DIST_MASK_3}, {"5", cv::DIST_MASK_5}, {"precise", cv::DIST_MASK_PRECISE}})
          .describe(
              "l2's approximation: a 3x3 or 5x5 mask, or "
              "precise (exact); l1 and c are exact with 3");
  static apex::Manifest manifest() {
    return filterManifest("Distance of each non-zero pixel of a binary image to the nearest zero pixel (8-bit, single channel)",
                          kImageIn, kDistances)
        .param(kDistanceType)
        .param(kMaskSize);
  }
  DistanceTransform() : ImageFilter("1", true, kImageIn, kDistances) {}

 private:
  void filter(const Image& in, Image& out) override {
    cv::distanceTransform(in.mat, out.mat, distance_type_.get(), mask_size_.get(), CV_32F);
    out.encoding = "32FC1";
  }
  apex::Choice<int> distance_type_{this, kDistanceType};
  apex::Choice<int> mask_size_{this, kMaskSize};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Flip, "apex_nodes/Flip");
APEX_REGISTER_NODE(apex_nodes::PyrDown, "apex_nodes/PyrDown");
APEX_REGISTER_NODE(apex_nodes::PyrUp, "apex_nodes/PyrUp");
APEX_REGISTER_NODE(apex_nodes::WarpPerspective, "apex_nodes/WarpPerspective");
APEX_REGISTER_NODE(apex_nodes::DistanceTransform, "apex_nodes/DistanceTransform");
