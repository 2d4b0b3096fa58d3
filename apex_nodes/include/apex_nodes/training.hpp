// Training a classifier for Classifier: what apex_train does (samples from a CSV file, or features
// of SampleExport's crops), as functions the tests call too.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/ml.hpp>
#include <string>
#include <vector>

#include "apex_nodes/learning.hpp"

namespace apex_nodes {

/** @brief Samples to train on: a CV_32F row of features and a label (>= 0) each. */
struct Samples {
  cv::Mat rows;
  std::vector<int> labels;
};

/** @brief Reads a CSV file of samples, a line each: "label,feature,feature,..." (the label a whole
 *  number >= 0; every line as many features as the first). A first line that does not start with
 *  a number (e.g. "label,f1,f2") is a header; blank lines are skipped. Throws std::invalid_argument
 *  "PATH line N: ..." for a malformed line, or naming the file if it cannot be read or is empty. */
Samples readCsv(const std::string& path);

/** @brief The features of crops (featureRow), with their labels. */
Samples featuresOf(const std::vector<cv::Mat>& crops, const std::vector<int>& labels, const FeatureSettings& settings);

/** @brief What to train, and how much to hold out. */
struct ModelOptions {
  std::string model = "svm";  ///< svm, rtrees, knn, mlp or boost
  double svm_c = 2.67, svm_gamma = 5.383;  ///< svm: C_SVC with an RBF kernel (OpenCV digits.py's values)
  int k = 3;  ///< knn: neighbours
  int trees = 100;  ///< rtrees: trees (at most 16 deep); boost: weak trees (two classes only)
  std::vector<int> hidden{64};  ///< mlp: neurons per hidden layer (outputs: one per label 0..the largest)
  int epochs = 300;  ///< mlp: RPROP iterations
  double validation = 0.2;  ///< share of the samples held out to measure the accuracy, 0..0.9
  unsigned seed = 1;  ///< the same seed, the same split (and MLP weights)
};

/** @brief A trained model, and how it did on the samples held out. */
struct TrainResult {
  std::string kind;  ///< ModelOptions::model
  cv::Ptr<cv::ml::StatModel> model;  ///< trained on the samples not held out
  std::string features;  ///< featureSummary of the features, recorded in the file ("" for a CSV's)
  std::vector<int> classes;  ///< the labels of all samples, sorted
  int train_samples = 0, validation_samples = 0;
  double validation_accuracy = 0;  ///< right / validation_samples, as Classifier labels them; 0 if none held out
  /** [true class][predicted class], by index in `classes`; a last column for labels not among them. */
  std::vector<std::vector<int>> confusion;

  /** @brief The confusion matrix as text: a row per true label, a column per predicted one. */
  std::string confusionTable() const;
  /** @brief The model file's text: OpenCV's (its first node e.g. opencv_ml_svm, so cv::Algorithm::load
   *  reads it), then `apex_features` if known. XML for a name ending in .xml, JSON for .json, else YAML. */
  std::string text(const std::string& path = "model.yaml") const;
  /** @brief Writes text(path) atomically (a reader sees the old file or the whole new one); throws
   *  std::runtime_error naming the file. */
  void save(const std::string& path) const;
};

/** @brief Holds a share of the samples out (a shuffle by `seed`), trains the model on the rest, and
 *  labels those held out as Classifier would (the model as read back from its file). Throws
 *  std::invalid_argument for unknown options, fewer than two classes, negative labels, or too
 *  few samples to hold some out. `features`: recorded with the model (featureSummary). */
TrainResult trainModel(const Samples& samples, const ModelOptions& options, const std::string& features = "");

}  // namespace apex_nodes
