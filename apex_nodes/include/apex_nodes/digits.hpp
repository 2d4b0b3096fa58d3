// Digits on signs: the features a crop gives, and a multi-layer perceptron (cv::ml::ANN_MLP)
// trained on them, saved with its feature settings in one file. Shared by apex_train_mlp,
// DigitClassifier and the tests, so training and classification see the same features.
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <opencv2/ml.hpp>
#include <string>
#include <vector>

namespace apex_nodes {

/** @brief How a crop becomes features; saved with the model. */
struct DigitFeatureSettings {
  int size = 16;  ///< the digit, scaled into size x size pixels
};

/** @brief The features of a sign's crop (gray or BGR, a dark sign with a light digit or the
 *  reverse): the digit's pixels (the class that does not touch the crop's border, Otsu's
 *  threshold), cut to their bounding box and scaled into a square, keeping the aspect ratio;
 *  one row of size*size floats in 0..1. Throws std::invalid_argument for an empty crop. */
cv::Mat digitFeatures(const cv::Mat& crop, const DigitFeatureSettings& settings);

/** @brief digitFeatures of each crop, a row each. */
cv::Mat digitFeatures(const std::vector<cv::Mat>& crops, const DigitFeatureSettings& settings);

struct DigitPrediction {
  int label = -1;
  double confidence = 0;  ///< softmax of the network's outputs, 0..1
};

struct TrainSettings {
  std::vector<int> hidden{64};  ///< neurons per hidden layer
  int epochs = 300;  ///< RPROP iterations in all
  int batch = 50;  ///< epochs between progress reports
  double validation = 0.2;  ///< share of the samples held out
  int augment = 3;  ///< varied copies of each training crop (slant, turn, size): 0 for none
  unsigned seed = 1;  ///< the same seed, the same split and weights
};

struct TrainProgress {
  int epochs = 0;
  double train_accuracy = 0, validation_accuracy = 0;
};

/** @brief A trained network, its classes and feature settings. */
class DigitModel {
 public:
  /** @brief Trains on sign crops with their `labels`: a share held out for validation, the rest
   *  with `augment` varied copies each; `progress` is called after every batch of epochs. Throws
   *  std::invalid_argument if there are fewer than two classes or too few crops to hold some out. */
  static DigitModel train(const std::vector<cv::Mat>& crops, const std::vector<int>& labels, const DigitFeatureSettings& features,
                          const TrainSettings& settings, const std::function<void(const TrainProgress&)>& progress = {});
  /** @brief Reads a model file; throws std::invalid_argument naming the file and what is wrong. */
  static DigitModel load(const std::string& path);
  /** @brief Writes the model atomically (a reader sees the old file or the whole new one);
   *  throws std::runtime_error naming the file. */
  void save(const std::string& path) const;

  DigitPrediction predict(const cv::Mat& features) const;
  DigitPrediction classify(const cv::Mat& crop) const { return predict(digitFeatures(crop, features_)); }
  /** @brief Share of `samples` (a row of digitFeatures each) predicted as `labels`. */
  double accuracy(const cv::Mat& samples, const std::vector<int>& labels) const;
  double accuracy(const std::vector<cv::Mat>& crops, const std::vector<int>& labels) const;

  const DigitFeatureSettings& features() const { return features_; }
  const std::vector<int>& classes() const { return classes_; }
  double validationAccuracy() const { return validation_accuracy_; }

 private:
  bool fits() const;  ///< the network's sizes and weights fit the features and classes
  cv::Ptr<cv::ml::ANN_MLP> mlp_;
  DigitFeatureSettings features_;
  std::vector<int> classes_;
  double validation_accuracy_ = 0;
};

}  // namespace apex_nodes
