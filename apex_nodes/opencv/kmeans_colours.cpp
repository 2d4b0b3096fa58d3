// KMeansColours: quantises an image to k colours (cv::kmeans over its pixels' colours): each pixel
// becomes the centre of its cluster, and the labels image says which cluster that is. Colour
// regions for a segmentation, or a palette. k-means starts from random centres: OpenCV's random
// generator is seeded before each frame, so a frame gives the same clusters every time.
#include <algorithm>
#include <opencv2/core.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;

class KMeansColours : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "8-bit, 1, 3 or 4 channels"};
  static inline const apex::OutputPort<Image> kQuantised{
      "image", "the input's encoding: each pixel the centre of its cluster (rounded to 8 bits)"};
  static inline const apex::OutputPort<Image> kLabels{"labels", "32SC1 of the image's size: each pixel's cluster, 0..k-1"};
  static inline const apex::ParamDecl<int> kK =
      param::integer("k").range(1, 64).step(1).init(8).describe("clusters: the colours left");
  static inline const apex::ParamDecl<int> kAttempts =
      param::integer("attempts").range(1, 20).step(1).init(3).describe("runs from other starts; the most compact is kept");
  static inline const apex::ParamDecl<int> kMaxCount =
      param::integer("max_count").range(1, 1000).step(1).init(10).describe("iterations per attempt at most");
  static inline const apex::ParamDecl<double> kEpsilon =
      param::number("epsilon")
          .range(0.0, 100.0)
          .step(0.01)
          .init(1.0)
          .describe("an attempt stops when no centre moves further (grey levels)");
  static inline const apex::ChoiceDecl<int> kFlags =
      param::choice<int>("flags", {{"pp_centers", cv::KMEANS_PP_CENTERS, "k-means++: spread-out starts"},
                                   {"random_centers", cv::KMEANS_RANDOM_CENTERS, "random starts"}})
          .describe("how each attempt chooses its first centres");
  static inline const apex::ParamDecl<int> kSeed =
      param::integer("seed")
          .range(0, 1000000000)
          .step(1)
          .init(1)
          .describe(
              "set in OpenCV's random generator (cv::setRNGSeed) before each frame: a frame gives the same clusters every time");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Quantises an image to k colours (cv::kmeans on its pixels): the image in its clusters' colours, and the labels")
        .inCategory("segmentation")
        .input(kImage)
        .output(kQuantised)
        .output(kLabels)
        .param(kK)
        .param(kAttempts)
        .param(kMaxCount)
        .param(kEpsilon)
        .param(kFlags)
        .param(kSeed);
  }
  void process() override {
    const Image& in = *image_.get();
    requireImage(in, "134");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("the image is " + imageWords(in) + "; it needs 8-bit pixels");
    const int k = k_.get();
    const std::size_t least = std::max(std::size_t(k), std::size_t(2));  // one pixel would be taken as a row of samples
    if (in.mat.total() < least)
      throw std::invalid_argument("k " + std::to_string(k) + " needs an image of at least " + std::to_string(least) +
                                  " pixels, got " + imageWords(in));
    in.mat.convertTo(samples_, CV_32F);  // a new continuous matrix: one row of channels per pixel below
    cv::setRNGSeed(seed_.get());
    cv::kmeans(samples_.reshape(1, int(in.mat.total())), k, best_labels_,
               cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, max_count_.get(), epsilon_.get()),
               attempts_.get(), flags_.get(), centers_);
    auto labels = labels_buffer_.next(in);
    best_labels_.reshape(1, in.mat.rows).copyTo(labels->mat);
    labels->encoding = "32SC1";
    auto quantised = image_buffer_.next(in);
    quantised->encoding = in.encoding;
    paint(labels->mat, in.mat.channels(), quantised->mat);
    image_out_.publish(quantised);
    labels_out_.publish(labels);
  }

 private:
  /** Each pixel the colour of its cluster's centre, rounded and saturated to 8 bits. */
  void paint(const cv::Mat& labels, int channels, cv::Mat& out) {
    centers_.convertTo(colours_, CV_8U);  // k rows of `channels` bytes
    out.create(labels.size(), CV_8UC(channels));
    for (int y = 0; y < labels.rows; ++y) {
      const int* label = labels.ptr<int>(y);
      uchar* pixel = out.ptr<uchar>(y);
      for (int x = 0; x < labels.cols; ++x, pixel += channels) std::copy_n(colours_.ptr<uchar>(label[x]), channels, pixel);
    }
  }

  apex::Input<Image> image_{this, kImage};
  apex::Output<Image> image_out_{this, kQuantised};
  apex::Output<Image> labels_out_{this, kLabels};
  apex::Param<int> k_{this, kK};
  apex::Param<int> attempts_{this, kAttempts};
  apex::Param<int> max_count_{this, kMaxCount};
  apex::Param<double> epsilon_{this, kEpsilon};
  apex::Choice<int> flags_{this, kFlags};
  apex::Param<int> seed_{this, kSeed};
  cv::Mat samples_, best_labels_, centers_, colours_;  // kept between frames: no allocation per frame
  OutputBuffer image_buffer_, labels_buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::KMeansColours, "apex_nodes/KMeansColours");
