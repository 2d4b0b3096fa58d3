// Superpixels: divides an image into small regions of even colour with OpenCV contrib's ximgproc
// (SLIC, SLICO, MSLIC, SEEDS or LSC): a label image and the mask of the regions' borders. A few
// hundred superpixels stand in for the pixels where a segmentation or a classifier per pixel would
// be too slow. Each parameter's description says which algorithms read it.
#include <cmath>
#include <opencv2/ximgproc/lsc.hpp>
#include <opencv2/ximgproc/seeds.hpp>
#include <opencv2/ximgproc/slic.hpp>

#include "apex/core/registry.hpp"
#include "apex_nodes/filter_options.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/output_buffer.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Superpixels : public apex::Node {
 public:
  /** The algorithms; SLIC's three are cv::ximgproc::SLICType's values. */
  enum Algorithm { kSlic = cv::ximgproc::SLIC, kSlico = cv::ximgproc::SLICO, kMslic = cv::ximgproc::MSLIC, kSeeds, kLsc };

  static inline const apex::InputPort<Image> kImage{"image", "8-bit, 1 or 3 channels"};
  static inline const apex::OutputPort<Image> kLabels{"labels", "32SC1 of the image's size: each pixel's superpixel, from 0"};
  static inline const apex::OutputPort<Image> kMask{"mask", "mono8: 255 on the superpixels' borders, else 0"};
  static inline const apex::OutputPort<int> kCount{"count", "how many superpixels"};
  static inline const apex::ChoiceDecl<Algorithm> kAlgorithm =
      param::choice<Algorithm>(
          "algorithm",
          {{"slic", kSlic, "clusters of colour and position grown from a grid"},
           {"slico", kSlico, "SLIC with a compactness of its own per superpixel"},
           {"mslic", kMslic, "manifold SLIC: smaller superpixels where the image has detail"},
           {"seeds", kSeeds, "colour histograms of blocks, refined from a grid"},
           {"lsc", kLsc, "linear spectral clustering; parallel in OpenCV, so a few border pixels can differ between runs"}})
          .init("slico");
  static inline const apex::ParamDecl<int> kRegionSize =
      param::integer("region_size")
          .range(2, 200)
          .step(1)
          .init(10)
          .describe("SLIC, SLICO, MSLIC, LSC: a superpixel's mean width, pixels");
  static inline const apex::ParamDecl<double> kRuler =
      param::number("ruler")
          .range(0.1, 100.0)
          .step(0.1)
          .init(10.0)
          .describe("SLIC, MSLIC: how much position weighs against colour; higher: rounder superpixels");
  static inline const apex::ParamDecl<double> kRatio =
      param::number("ratio").range(0.01, 1.0).step(0.005).init(0.075).describe("LSC: how compact superpixels are");
  static inline const apex::ParamDecl<int> kMinElementSize =
      param::integer("min_element_size")
          .range(0, 100)
          .step(1)
          .init(25)
          .describe(
              "SLIC, SLICO, MSLIC: superpixels under this percent of the mean size join a neighbour; LSC: those under this "
              "many pixels; 0: none join (enforceLabelConnectivity not called)");
  static inline const apex::ParamDecl<int> kNumIterations =
      param::integer("num_iterations").range(1, 100).step(1).init(10).describe("all: refining passes");
  static inline const apex::ParamDecl<int> kNumSuperpixels = param::integer("num_superpixels")
                                                                 .range(10, 5000)
                                                                 .step(1)
                                                                 .init(400)
                                                                 .describe("SEEDS: how many, at most (its grid may give fewer)");
  static inline const apex::ParamDecl<int> kNumLevels =
      param::integer("num_levels").range(2, 8).step(1).init(4).describe("SEEDS: block levels; more: finer borders, slower");
  static inline const apex::ParamDecl<int> kPrior =
      param::integer("prior").range(0, 5).step(1).init(2).describe("SEEDS: how smooth the borders are; 0: not smoothed");
  static inline const apex::ParamDecl<int> kHistogramBins =
      param::integer("histogram_bins").range(2, 8).step(1).init(5).describe("SEEDS: per channel");
  static inline const apex::ParamDecl<bool> kDoubleStep = param::flag("double_step").describe("SEEDS: each block level twice");
  static inline const apex::ParamDecl<bool> kThickLine =
      param::flag("thick_line").describe("the mask: every pixel at a border (on) or a line one pixel wide (off)");
  static apex::Manifest manifest() {
    return apex::Manifest("Divides an image into superpixels, small regions of even colour (ximgproc's SLIC, SEEDS, LSC)")
        .inCategory("segmentation")
        .input(kImage)
        .output(kLabels)
        .output(kMask)
        .output(kCount)
        .param(kAlgorithm)
        .param(kRegionSize)
        .param(kRuler)
        .param(kRatio)
        .param(kMinElementSize)
        .param(kNumIterations)
        .param(kNumSuperpixels)
        .param(kNumLevels)
        .param(kPrior)
        .param(kHistogramBins)
        .param(kDoubleStep)
        .param(kThickLine);
  }
  void process() override {
    const Image& in = *image_.get();
    requireImage(in, "13");
    if (in.mat.depth() != CV_8U) throw std::invalid_argument("the image is " + imageWords(in) + "; it needs 8-bit pixels");
    auto labels = labels_buffer_.next(in);
    auto mask = mask_buffer_.next(in);
    labels->encoding = "32SC1";
    mask->encoding = "mono8";
    int count = 0;
    const Algorithm algorithm = algorithm_.get();
    if (algorithm == kSeeds) {
      count = seeds(in.mat, labels->mat, mask->mat);
    } else if (algorithm == kLsc) {
      requireRegionSize(in);
      const auto lsc = cv::ximgproc::createSuperpixelLSC(in.mat, region_size_.get(), float(ratio_.get()));
      count = finish(*lsc, labels->mat, mask->mat);
    } else {
      requireRegionSize(in);
      const auto slic = cv::ximgproc::createSuperpixelSLIC(in.mat, algorithm, region_size_.get(), float(ruler_.get()));
      count = finish(*slic, labels->mat, mask->mat);
    }
    labels_out_.publish(labels);
    mask_out_.publish(mask);
    count_out_.publish(count);
  }

 private:
  /** Refines a SLIC or an LSC, joins its small superpixels to neighbours, and reads the result. */
  template <class Segmentation>
  int finish(Segmentation& s, cv::Mat& labels, cv::Mat& mask) const {
    s.iterate(num_iterations_.get());
    if (min_element_size_.get() > 0) s.enforceLabelConnectivity(min_element_size_.get());
    s.getLabels(labels);
    s.getLabelContourMask(mask, thick_line_.get());
    return s.getNumberOfSuperpixels();
  }
  int seeds(const cv::Mat& image, cv::Mat& labels, cv::Mat& mask) const {
    requireSeedsGrid(image);
    const auto s =
        cv::ximgproc::createSuperpixelSEEDS(image.cols, image.rows, image.channels(), num_superpixels_.get(), num_levels_.get(),
                                            prior_.get(), histogram_bins_.get(), double_step_.get());
    s->iterate(image, num_iterations_.get());
    s->getLabels(labels);
    s->getLabelContourMask(mask, thick_line_.get());
    return s->getNumberOfSuperpixels();
  }
  /** SLIC and LSC seed a grid of region_size cells: under two cells across or down, LSC's grid
   *  divides by zero and SLIC's can be empty. */
  void requireRegionSize(const Image& in) const {
    const int s = region_size_.get();
    if (in.mat.cols < 2 * s || in.mat.rows < 2 * s)
      throw std::invalid_argument("region_size " + std::to_string(s) + " needs an image of at least " + std::to_string(2 * s) +
                                  "x" + std::to_string(2 * s) + " pixels, got " + imageWords(in));
  }
  /** SEEDS' grid as createSuperpixelSEEDS lays it: under 2 superpixels across or down, or more
   *  than the pixels, its block levels divide by zero. */
  void requireSeedsGrid(const cv::Mat& image) const {
    const int n = num_superpixels_.get();
    const int down = int(std::sqrt(float(n) * float(image.rows) / float(image.cols))), across = down * image.cols / image.rows;
    if (down < 2 || across < 2 || down > image.rows || across > image.cols)
      throw std::invalid_argument("num_superpixels " + std::to_string(n) + " lays a grid of " + std::to_string(across) + "x" +
                                  std::to_string(down) + " on a " + std::to_string(image.cols) + "x" +
                                  std::to_string(image.rows) + " image; SEEDS needs 2x2 at least, one pixel each at most");
  }

  apex::Input<Image> image_{this, kImage};
  apex::Output<Image> labels_out_{this, kLabels};
  apex::Output<Image> mask_out_{this, kMask};
  apex::Output<int> count_out_{this, kCount};
  apex::Choice<Algorithm> algorithm_{this, kAlgorithm};
  apex::Param<int> region_size_{this, kRegionSize};
  apex::Param<double> ruler_{this, kRuler};
  apex::Param<double> ratio_{this, kRatio};
  apex::Param<int> min_element_size_{this, kMinElementSize};
  apex::Param<int> num_iterations_{this, kNumIterations};
  apex::Param<int> num_superpixels_{this, kNumSuperpixels};
  apex::Param<int> num_levels_{this, kNumLevels};
  apex::Param<int> prior_{this, kPrior};
  apex::Param<int> histogram_bins_{this, kHistogramBins};
  apex::Param<bool> double_step_{this, kDoubleStep};
  apex::Param<bool> thick_line_{this, kThickLine};
  OutputBuffer labels_buffer_, mask_buffer_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Superpixels, "apex_nodes/Superpixels");
