// Learning on regions: what FeatureExtract computes from each region of an image (Features), the
// cv::ml model Classifier labels them with (LearnedModel: any classifier OpenCV saved, its type
// found in the file), and how apex_train makes one (training.hpp). Shared by the nodes, the tool
// and the tests, so that training and classification see the same features.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/ml.hpp>
#include <string>
#include <vector>

#include "apex/core/declare.hpp"
#include "apex_nodes/types.hpp"

namespace apex_nodes {

/** @brief A row of features per region of one image (FeatureExtract), with the regions themselves
 *  so that a classifier can label them, and the header of the regions. */
struct Features {
  std_msgs::Header header;
  cv::Mat rows;  ///< CV_32F, regions->regions.size() rows of `length` floats, in the regions' order
  int length = 0;  ///< floats per row, fixed by the method's settings (also with no regions)
  std::vector<uchar> valid;  ///< per row: 0 when the region lies outside the image (its row is zeros)
  std::shared_ptr<const Regions> regions;
  std::string settings;  ///< the method and its settings (featureSummary), e.g. "hog size=20 cells=2 bins=16 deskew=0"
};

inline const std_msgs::Header& headerOf(const Features& f) { return f.header; }

/** @brief A feature method (FeatureSettings); by name: featureMethods(). */
enum class FeatureMethod { kHog, kColorHistogram, kHuMoments, kRawPixels };
/** @brief color_histogram's channels; by name: colorSpaces(). */
enum class ColorSpace { kHsv, kBgr };

/** @brief How a region becomes a row of features. Lengths:
 *   - hog: (cells-1)^2 * 4 * bins. cv::HOGDescriptor on the region in gray, scaled to size x size
 *     (INTER_AREA; deskewed first if `deskew`): cells of size/cells pixels, blocks of 2x2 cells a
 *     cell apart, `bins` signed orientations (0..360 degrees), L2-Hys normalised. cells=2 is
 *     OpenCV's digits.py layout: one block of four cells, 4 * bins floats.
 *   - color_histogram: 3 * bins. A histogram of `bins` per channel (hsv: H over 0..180, S and V
 *     over 0..256; bgr: each over 0..256), each the share of the region's pixels (sums to 1).
 *   - hu_moments: 7. The Hu moments of the region's Otsu mask (bright pixels; `binary`) or of its
 *     gray levels, each log-scaled: -sign(h) * log10(|h|), 0 for 0.
 *   - raw_pixels: size * size. The region in gray, scaled to size x size (INTER_AREA; deskewed if
 *     `deskew`), row by row, 0..1.
 *  Gray: a colour region is converted (BGR or BGRA); 16-bit pixels are scaled by 1/257, float
 *  ones (0..1) by 255. Deskew is digits.py's: the shear that makes the second-order moment mu11
 *  zero (none when |mu02| < 0.01). */
struct FeatureSettings {
  FeatureMethod method = FeatureMethod::kHog;
  int size = 20;  ///< hog, raw_pixels: the square the region is scaled into
  int cells = 2;  ///< hog: cells per side (size must be a multiple)
  int bins = 16;  ///< hog: orientations per cell; color_histogram: bins per channel
  bool deskew = false;  ///< hog, raw_pixels
  ColorSpace space = ColorSpace::kHsv;  ///< color_histogram
  bool binary = true;  ///< hu_moments: of the Otsu mask, else of the gray levels
};

/** @brief The methods by name (hog, color_histogram, hu_moments, raw_pixels), in FeatureExtract's
 *  order: its `method` choice, apex_train's --features and featureSummary read this one table. */
const std::vector<apex::Option<FeatureMethod>>& featureMethods();

/** @brief color_histogram's spaces by name (hsv, bgr): FeatureExtract's `color_space`, apex_train's
 *  --space and featureSummary read this one table. */
const std::vector<apex::Option<ColorSpace>>& colorSpaces();

/** @brief Floats per row; throws std::invalid_argument naming the setting that does not fit. */
int featureLength(const FeatureSettings& settings);

/** @brief The method with the settings it uses, e.g. "hog size=20 cells=2 bins=16 deskew=0";
 *  recorded in a model apex_train writes, compared by Classifier. */
std::string featureSummary(const FeatureSettings& settings);

/** @brief The features of one crop (1, 3 or 4 channels): a 1 x featureLength row of CV_32F.
 *  Throws std::invalid_argument for an empty crop or settings that do not fit. */
cv::Mat featureRow(const cv::Mat& crop, const FeatureSettings& settings);

/** @brief One prediction: the label and how sure the model is, 0..1. */
struct Prediction {
  int label = -1;
  double confidence = 0;
};

/** @brief A trained cv::ml model, whatever its type, read as OpenCV saved it; optionally with the
 *  feature settings it was trained on (apex_train records them as `apex_features`). Confidence:
 *   - mlp (ANN_MLP): the softmax of the outputs (sharpness 10) at the best, as DigitClassifier's;
 *     the label is the best output's index.
 *   - svm: 1; a two-class C_SVC or NU_SVC gets 1 / (1 + exp(-2|d|)) from its decision value d
 *     (RAW_OUTPUT): 0.5 on the boundary, 0.88 on the margin.
 *   - rtrees: the share of the trees that voted for the label (getVotes).
 *   - knn (KNearest): the share of the k nearest neighbours (its default k) with the label.
 *   - boost, dtrees, lr, nbayes: 1. */
class LearnedModel {
 public:
  /** @brief Reads a model file (YAML, XML or JSON, as OpenCV writes them; the type from its first
   *  node, e.g. opencv_ml_svm). Throws std::invalid_argument starting "the model 'PATH' ", saying
   *  what is wrong (cannot be read, damaged, not a model OpenCV's ml module classifies with). */
  static LearnedModel load(const std::string& path);
  /** @brief The same, from a model file's text; `name` stands for the path in errors. */
  static LearnedModel parse(const std::string& text, const std::string& name);

  /** @brief A label and confidence per row of `rows` (CV_32F, varCount() columns). */
  std::vector<Prediction> predict(const cv::Mat& rows) const;

  const std::string& kind() const { return kind_; }  ///< svm, rtrees, knn, mlp, boost, dtrees, lr or nbayes
  int varCount() const { return var_count_; }  ///< features per sample it takes
  const std::string& features() const { return features_; }  ///< featureSummary it was trained on, or ""

 private:
  LearnedModel() = default;
  static LearnedModel read(cv::FileStorage& fs, const std::string& name);
  cv::Ptr<cv::ml::StatModel> model_;
  std::string kind_, features_;
  int var_count_ = 0;
  int svm_classes_ = 0;  // an SVM's classes (2: confidence from its decision value)
};

}  // namespace apex_nodes

APEX_TYPE_NAME(apex_nodes::Features, "apex_nodes/Features");
