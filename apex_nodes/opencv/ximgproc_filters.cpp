// Edge-preserving smoothing from OpenCV contrib's ximgproc: GuidedFilter, AnisotropicDiffusion,
// EdgePreservingFilter. Each smooths flat areas and noise but not across edges, as a step before
// a threshold or a segmentation that noise would break up.
#include <opencv2/ximgproc.hpp>

#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_filter.hpp"

namespace apex_nodes {
namespace param = apex::param;

namespace {
constexpr int kSameDepth = -1;  // the ddepth choice's "same": the input's
}  // namespace

class GuidedFilter : public ImageFilter {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit or 32F, any number of channels"};
  static inline const apex::InputPort<Image> kGuide{
      "guide",
      "optional: the image whose edges are kept (8U, 16U or 32F; of more than 3 channels the first 3), of the image's size; "
      "unconnected or Nothing: the image guides itself",
      true};
  static inline const apex::ParamDecl<int> kRadius =
      param::integer("radius").range(1, 100).step(1).init(4).describe("the window's radius in pixels (a window of 2 radius + 1)");
  static inline const apex::ParamDecl<double> kEps =
      param::number("eps")
          .range(0.0, 100000.0)
          .step(1.0)
          .init(400.0)
          .describe(
              "regularisation, in the guide's intensity units squared: windows whose variance is well below it are smoothed, "
              "those well above keep their edges (an 8-bit guide: 400 is a deviation of 20 grey levels)");
  static inline const apex::ChoiceDecl<int> kDdepth =
      param::choice<int>("ddepth", {{"same", kSameDepth}, {"8U", CV_8U}, {"16U", CV_16U}, {"32F", CV_32F}, {"64F", CV_64F}})
          .describe("the result's depth");
  static apex::Manifest manifest() {
    return filterManifest(
               "Smooths an image but keeps the edges of a guide, the image itself unless one is connected (He's guided "
               "filter, cv::ximgproc::guidedFilter)",
               kImage)
        .input(kGuide)
        .param(kRadius)
        .param(kEps)
        .param(kDdepth);
  }
  GuidedFilter() : ImageFilter("1234", false, kImage) {}

 private:
  void filter(const Image& in, Image& out) override {
    const int depth = in.mat.depth();
    if (depth != CV_8U && depth != CV_32F)
      throw std::invalid_argument("the image is " + imageWords(in) + "; it needs 8-bit or 32F pixels");
    const auto guide = guide_.get();  // nullptr: unconnected, or Nothing this firing
    if (guide) requireGuide(*guide, in);
    const int ddepth = ddepth_.get() == kSameDepth ? depth : ddepth_.get();
    cv::ximgproc::guidedFilter(guide ? guide->mat : in.mat, in.mat, out.mat, radius_.get(), eps_.get(), ddepth);
    out.encoding = encodingOf(in, in.mat.channels(), ddepth);
  }
  static void requireGuide(const Image& guide, const Image& in) {
    if (guide.mat.empty()) throw std::invalid_argument("received an empty guide");
    const int depth = guide.mat.depth();
    if (depth != CV_8U && depth != CV_16U && depth != CV_32F)
      throw std::invalid_argument("the guide is " + imageWords(guide) + "; it needs 8U, 16U or 32F pixels");
    if (guide.mat.size() != in.mat.size())
      throw std::invalid_argument("the guide is " + imageWords(guide) + ", the image " + imageWords(in) +
                                  ": they need the same size");
  }
  apex::Input<Image> guide_{this, kGuide};
  apex::Param<int> radius_{this, kRadius};
  apex::Param<double> eps_{this, kEps};
  apex::Choice<int> ddepth_{this, kDdepth};
};

class AnisotropicDiffusion : public ImageFilter {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit, 3 channels (bgr8, rgb8)"};
  static inline const apex::ParamDecl<double> kAlpha =
      param::number("alpha").range(0.01, 1.0).step(0.01).init(0.1).describe("how far each iteration steps (normally 0 to 1)");
  static inline const apex::ParamDecl<double> kK =
      param::number("k")
          .range(0.001, 1.0)
          .step(0.001)
          .init(0.02)
          .describe(
              "sensitivity to edges (OpenCV's K): neighbours that differ by much more than K x 765 (the three channels' "
              "differences summed) are hardly mixed");
  static inline const apex::ParamDecl<int> kNiters =
      param::integer("niters").range(0, 100).step(1).init(10).describe("iterations; 0: the frame as it came");
  static apex::Manifest manifest() {
    return filterManifest(
               "Perona-Malik anisotropic diffusion: smooths within regions, not across their edges "
               "(cv::ximgproc::anisotropicDiffusion)",
               kImage)
        .param(kAlpha)
        .param(kK)
        .param(kNiters);
  }
  AnisotropicDiffusion() : ImageFilter("3", true, kImage) {}

 private:
  bool passesThrough(const Image&) const override { return niters_.get() == 0; }  // OpenCV copies it
  void filter(const Image& in, Image& out) override {
    cv::ximgproc::anisotropicDiffusion(in.mat, out.mat, float(alpha_.get()), float(k_.get()), niters_.get());
  }
  apex::Param<double> alpha_{this, kAlpha};
  apex::Param<double> k_{this, kK};
  apex::Param<int> niters_{this, kNiters};
};

class EdgePreservingFilter : public ImageFilter {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit, 3 channels (bgr8, rgb8)"};
  static inline const apex::ParamDecl<int> kD =
      param::integer("d").range(3, 31).step(1).init(9).describe("the side of the windows averaged, pixels");
  static inline const apex::ParamDecl<double> kThreshold =
      param::number("threshold")
          .range(0.0, 450.0)
          .step(1.0)
          .init(20.0)
          .describe(
              "colour distance (Euclidean, 0 to 255 per channel) that parts noise from detail: a window whose pixels lie "
              "within it of their mean on average is smoothed, one beyond it (an edge) is left out");
  static apex::Manifest manifest() {
    return filterManifest(
               "Removes Gaussian and salt-and-pepper noise but keeps edges (Reich's filter, "
               "cv::ximgproc::edgePreservingFilter; slow: a d x d window around every pixel, one thread)",
               kImage)
        .param(kD)
        .param(kThreshold);
  }
  EdgePreservingFilter() : ImageFilter("3", true, kImage) {}

 private:
  void filter(const Image& in, Image& out) override {
    cv::ximgproc::edgePreservingFilter(in.mat, out.mat, d_.get(), threshold_.get());
  }
  apex::Param<int> d_{this, kD};
  apex::Param<double> threshold_{this, kThreshold};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::GuidedFilter, "apex_nodes/GuidedFilter");
APEX_REGISTER_NODE(apex_nodes::AnisotropicDiffusion, "apex_nodes/AnisotropicDiffusion");
APEX_REGISTER_NODE(apex_nodes::EdgePreservingFilter, "apex_nodes/EdgePreservingFilter");
