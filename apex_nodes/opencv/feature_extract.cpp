// FeatureExtract: a row of features per region of an image (apex_nodes/learning.hpp has the
// methods and their lengths), for Classifier or for training (apex_train reads the same features
// from SampleExport's crops). The regions go along, shared, so that a classifier can label them.
#include "apex/core/registry.hpp"
#include "apex_nodes/image_check.hpp"
#include "apex_nodes/learning.hpp"

namespace apex_nodes {
namespace param = apex::param;

class FeatureExtract : public apex::Node {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "the image the regions were found in"};
  static inline const apex::InputPort<Regions> kRegions{"regions", "e.g. BlobDetection's"};
  static inline const apex::OutputPort<Features> kFeatures{
      "features", "a row per region, in the regions' order (zeros for a region outside the image), with the regions"};
  static inline const apex::ChoiceDecl<FeatureMethod> kMethod =
      param::choice<FeatureMethod>("method", featureMethods())
          .describe("hog: (cells-1)^2*4*bins floats; color_histogram: 3*bins; hu_moments: 7; raw_pixels: size*size");
  static inline const apex::ParamDecl<int> kSize = param::integer("size").range(2, 512).init(20).describe(
      "hog, raw_pixels: the region is scaled into size x size pixels (hog: a multiple of cells)");
  static inline const apex::ParamDecl<int> kCells =
      param::integer("cells").range(2, 16).init(2).describe("hog: cells per side, in blocks of 2x2 cells a cell apart");
  static inline const apex::ParamDecl<int> kBins = param::integer("bins").range(2, 64).init(16).describe(
      "hog: orientations per cell (0..360 degrees); color_histogram: bins per channel");
  static inline const apex::ParamDecl<bool> kDeskew =
      param::flag("deskew").describe("hog, raw_pixels: straighten slanted strokes first (OpenCV's digits.py)");
  static inline const apex::ChoiceDecl<ColorSpace> kSpace =
      param::choice<ColorSpace>("color_space", colorSpaces()).describe("color_histogram: the channels counted");
  static inline const apex::ParamDecl<bool> kBinary =
      param::flag("binary").init(true).describe("hu_moments: of the Otsu mask (bright pixels), else of the gray levels");
  static apex::Manifest manifest() {
    return apex::Manifest("Computes a feature vector per region (HOG, colour histogram, Hu moments or raw pixels)")
        .inCategory("learning")
        .input(kImage)
        .input(kRegions)
        .output(kFeatures)
        .param(kMethod)
        .param(kSize)
        .param(kCells)
        .param(kBins)
        .param(kDeskew)
        .param(kSpace)
        .param(kBinary);
  }
  void process() override {
    const Image& image = *image_.get();
    const std::shared_ptr<const Regions> in = regions_.get();
    requireImage(image);
    FeatureSettings s;
    s.method = method_.get(), s.size = size_.get(), s.cells = cells_.get(), s.bins = bins_.get();
    s.deskew = deskew_.get(), s.space = space_.get(), s.binary = binary_.get();
    auto out = std::make_shared<Features>();
    out->header = in->header;
    out->length = featureLength(s);  // throws for settings that do not fit, naming them
    out->settings = featureSummary(s);
    out->regions = in;
    out->rows = cv::Mat::zeros(static_cast<int>(in->regions.size()), out->length, CV_32F);
    out->valid.assign(in->regions.size(), 0);
    const cv::Rect frame(0, 0, image.mat.cols, image.mat.rows);
    for (std::size_t i = 0; i < in->regions.size(); ++i) {
      const cv::Rect box = in->regions[i].box & frame;
      if (box.empty()) continue;
      featureRow(image.mat(box), s).copyTo(out->rows.row(static_cast<int>(i)));
      out->valid[i] = 1;
    }
    features_.publish(std::move(out));
  }

 private:
  apex::Input<Image> image_{this, kImage};
  apex::Input<Regions> regions_{this, kRegions};
  apex::Output<Features> features_{this, kFeatures};
  apex::Choice<FeatureMethod> method_{this, kMethod};
  apex::Param<int> size_{this, kSize};
  apex::Param<int> cells_{this, kCells};
  apex::Param<int> bins_{this, kBins};
  apex::Param<bool> deskew_{this, kDeskew};
  apex::Choice<ColorSpace> space_{this, kSpace};
  apex::Param<bool> binary_{this, kBinary};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::FeatureExtract, "apex_nodes/FeatureExtract");
