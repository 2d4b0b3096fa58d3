// GrabCut: cuts an object out of its background given a rectangle around it (cv::grabCut). The
// pixels outside the rectangle are background; inside, colour models of object and background
// (Gaussian mixtures) and a graph cut decide, refined over iter_count rounds. The rectangle is the
// parameters', or the first box of a detector's regions when that input is connected.
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;

class GrabCut : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit, 3 channels (bgr8 or rgb8)"};
  static inline const apex::InputPort<Regions> kRegions{
      "regions", "if connected: the first region's box is the rectangle (no region: an empty mask)", true};
  static inline const apex::OutputPort<Image> kMask{"mask", "mono8: 255 on the object (certain or probable), else 0"};
  static inline const apex::ParamDecl<int> kX =
      param::integer("x").range(0, 10000).step(1).init(20).describe("the rectangle's left edge, pixels");
  static inline const apex::ParamDecl<int> kY =
      param::integer("y").range(0, 10000).step(1).init(20).describe("the rectangle's top edge, pixels");
  static inline const apex::ParamDecl<int> kWidth = param::integer("width").range(1, 10000).step(1).init(200).describe("pixels");
  static inline const apex::ParamDecl<int> kHeight =
      param::integer("height").range(1, 10000).step(1).init(200).describe("pixels");
  static inline const apex::ParamDecl<int> kIterCount =
      param::integer("iter_count").range(1, 20).step(1).init(5).describe("rounds of colour models and graph cut");
  static inline const apex::ParamDecl<int> kSeed =
      param::integer("seed")
          .range(0, 1000000000)
          .step(1)
          .init(1)
          .describe(
              "set in OpenCV's random generator (cv::setRNGSeed) before each frame: a frame gives the same mask every time");
  static apex::Manifest manifest() {
    return apex::Manifest("Cuts the object in a rectangle out of its background (cv::grabCut): a mask of the object")
        .inCategory("segmentation")
        .input(kImage)
        .input(kRegions)
        .output(kMask)
        .param(kX)
        .param(kY)
        .param(kWidth)
        .param(kHeight)
        .param(kIterCount)
        .param(kSeed);
  }
  void process() override {
    const Image& in = *image_.get();
    requireImage(in, "3");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("the image is " + imageWords(in) + "; it needs 8-bit pixels");
    cv::Rect wanted(x_.get(), y_.get(), width_.get(), height_.get());
    auto out = buffer_.next(in);
    out->encoding = "mono8";
    if (auto regions = regions_.get()) {
      if (regions->regions.empty()) {  // nothing detected: nothing to cut out
        out->mat.create(in.mat.size(), CV_8UC1);
        out->mat.setTo(cv::Scalar::all(0));
        mask_out_.publish(out);
        return;
      }
      wanted = regions->regions.front().box;
    }
    const cv::Rect rect = inside(wanted, in);
    cv::Mat bgd_model, fgd_model;  // learnt anew each frame (GC_INIT_WITH_RECT)
    cv::setRNGSeed(seed_.get());  // grabCut starts its colour models with k-means++, which draws from cv::theRNG()
    cv::grabCut(in.mat, mask_, rect, bgd_model, fgd_model, iter_count_.get(), cv::GC_INIT_WITH_RECT);
    cv::bitwise_and(mask_, cv::Scalar(1), out->mat);  // GC_FGD (1) and GC_PR_FGD (3): the odd classes
    out->mat.convertTo(out->mat, CV_8U, 255);
    mask_out_.publish(out);
  }

 private:
  /** The part of `wanted` within the image; refused when it leaves too few pixels inside or out:
   *  grabCut learns 5 colours of each side from them (an OpenCV assertion otherwise). */
  static cv::Rect inside(const cv::Rect& wanted, const Image& in) {
    constexpr int kMinPixels = 5;
    const cv::Rect rect = wanted & cv::Rect(0, 0, in.mat.cols, in.mat.rows);
    const std::string words = "the rectangle " + std::to_string(wanted.x) + "," + std::to_string(wanted.y) + " " +
                              std::to_string(wanted.width) + "x" + std::to_string(wanted.height);
    if (rect.area() < kMinPixels)
      throw std::invalid_argument(words + " has fewer than " + std::to_string(kMinPixels) + " pixels in the image " +
                                  imageWords(in) + ": GrabCut learns the object from them");
    if (double(in.mat.total()) - rect.area() < kMinPixels)
      throw std::invalid_argument(words + " leaves fewer than " + std::to_string(kMinPixels) + " pixels of the image " +
                                  imageWords(in) + " outside it: GrabCut learns the background from them");
    return rect;
  }

  apex::Input<Image> image_{this, kImage};
  apex::Input<Regions> regions_{this, kRegions};
  apex::Output<Image> mask_out_{this, kMask};
  apex::Param<int> x_{this, kX};
  apex::Param<int> y_{this, kY};
  apex::Param<int> width_{this, kWidth};
  apex::Param<int> height_{this, kHeight};
  apex::Param<int> iter_count_{this, kIterCount};
  apex::Param<int> seed_{this, kSeed};
  cv::Mat mask_;  // grabCut's classes per pixel (GC_BGD...), kept between frames: no allocation per frame
  OutputBuffer buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::GrabCut, "apex_nodes/GrabCut");
