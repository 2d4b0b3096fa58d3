// Features of regions and learned models of any cv::ml type (see apex_nodes/learning.hpp).
#include "apex_nodes/learning.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>
#include <sstream>
#include <stdexcept>

namespace apex_nodes {
namespace {

constexpr double kMlpSharpness = 10;  // the softmax's, as DigitModel::predict (digits.cpp)

/** The crop as 8-bit pixels of its channels: 16-bit ones scaled by 1/257, float ones (0..1) by 255. */
cv::Mat depth8(const cv::Mat& crop) {
  if (crop.depth() == CV_8U) return crop;
  const double scale = crop.depth() == CV_16U ? 1.0 / 257 : crop.depth() == CV_32F || crop.depth() == CV_64F ? 255.0 : 1.0;
  cv::Mat out;
  crop.convertTo(out, CV_8U, scale);
  return out;
}

cv::Mat gray8(const cv::Mat& crop) {
  const cv::Mat in = depth8(crop);
  cv::Mat gray;
  switch (in.channels()) {
    case 1:
      return in;
    case 3:
      cv::cvtColor(in, gray, cv::COLOR_BGR2GRAY);
      return gray;
    case 4:
      cv::cvtColor(in, gray, cv::COLOR_BGRA2GRAY);
      return gray;
  }
  throw std::invalid_argument("cannot take features from " + std::to_string(in.channels()) + "-channel regions");
}

cv::Mat bgr8(const cv::Mat& crop) {
  const cv::Mat in = depth8(crop);
  cv::Mat bgr;
  switch (in.channels()) {
    case 1:
      cv::cvtColor(in, bgr, cv::COLOR_GRAY2BGR);
      return bgr;
    case 3:
      return in;
    case 4:
      cv::cvtColor(in, bgr, cv::COLOR_BGRA2BGR);
      return bgr;
  }
  throw std::invalid_argument("cannot take features from " + std::to_string(in.channels()) + "-channel regions");
}

/** digits.py's deskew: the shear (about the middle row) that makes mu11 zero. */
cv::Mat deskewed(const cv::Mat& gray) {
  const cv::Moments m = cv::moments(gray);
  if (std::abs(m.mu02) < 1e-2) return gray.clone();
  const double skew = m.mu11 / m.mu02;
  const cv::Mat warp = (cv::Mat_<double>(2, 3) << 1, skew, -0.5 * gray.rows * skew, 0, 1, 0);
  cv::Mat out;
  cv::warpAffine(gray, out, warp, gray.size(), cv::WARP_INVERSE_MAP | cv::INTER_LINEAR);
  return out;
}

/** The crop in gray, scaled to size x size, deskewed if asked: a Mat of its own (never a view:
 *  HOG would read the pixels around a view). */
cv::Mat square(const cv::Mat& crop, const FeatureSettings& s) {
  cv::Mat out;
  cv::resize(gray8(crop), out, cv::Size(s.size, s.size), 0, 0, cv::INTER_AREA);
  return s.deskew ? deskewed(out) : out;
}

cv::Mat hog(const cv::Mat& crop, const FeatureSettings& s) {
  const int cell = s.size / s.cells;
  const cv::HOGDescriptor descriptor(cv::Size(s.size, s.size), cv::Size(2 * cell, 2 * cell), cv::Size(cell, cell),
                                     cv::Size(cell, cell), s.bins, 1, -1, cv::HOGDescriptor::L2Hys, 0.2, false,
                                     cv::HOGDescriptor::DEFAULT_NLEVELS, true);
  std::vector<float> values;
  descriptor.compute(square(crop, s), values, cv::Size(s.size, s.size), cv::Size(0, 0));
  return cv::Mat(values, true).reshape(1, 1);
}

cv::Mat colorHistogram(const cv::Mat& crop, const FeatureSettings& s) {
  cv::Mat image = bgr8(crop);  // may be the input's pixels: never written
  if (s.space == ColorSpace::kHsv) {
    cv::Mat hsv;
    cv::cvtColor(image, hsv, cv::COLOR_BGR2HSV);
    image = hsv;
  }
  cv::Mat row(1, 3 * s.bins, CV_32F);
  const double pixels = static_cast<double>(image.total());
  for (int c = 0; c < 3; ++c) {
    const float top = s.space == ColorSpace::kHsv && c == 0 ? 180.f : 256.f;
    const float range[] = {0.f, top};
    const float* ranges[] = {range};
    cv::Mat hist;
    cv::calcHist(&image, 1, &c, cv::Mat(), hist, 1, &s.bins, ranges);
    hist.reshape(1, 1).convertTo(row.colRange(c * s.bins, (c + 1) * s.bins), CV_32F, 1.0 / pixels);
  }
  return row;
}

cv::Mat huMoments(const cv::Mat& crop, const FeatureSettings& s) {
  const cv::Mat gray = gray8(crop);  // may be the input's pixels: never written
  cv::Mat mask;
  if (s.binary) cv::threshold(gray, mask, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
  double hu[7];
  cv::HuMoments(cv::moments(s.binary ? mask : gray, s.binary), hu);
  cv::Mat row(1, 7, CV_32F);
  for (int i = 0; i < 7; ++i)
    row.at<float>(i) = hu[i] == 0 ? 0.f : static_cast<float>(-std::copysign(1.0, hu[i]) * std::log10(std::abs(hu[i])));
  return row;
}

cv::Mat rawPixels(const cv::Mat& crop, const FeatureSettings& s) {
  cv::Mat row;
  square(crop, s).reshape(1, 1).convertTo(row, CV_32F, 1.0 / 255);
  return row;
}

/** The kinds of model by the name OpenCV gives their file's first node. */
struct Kind {
  const char* node;
  const char* kind;
};
const Kind kKinds[] = {{"opencv_ml_svm", "svm"},      {"opencv_ml_rtrees", "rtrees"}, {"opencv_ml_knn", "knn"},
                       {"opencv_ml_kdtree", "knn"},   {"opencv_ml_ann_mlp", "mlp"},   {"opencv_ml_boost", "boost"},
                       {"opencv_ml_dtree", "dtrees"}, {"opencv_ml_dtrees", "dtrees"}, {"opencv_ml_lr", "lr"},
                       {"opencv_ml_nbayes", "nbayes"}};

/** The name of `value` in a table of options. */
template <class V>
std::string nameOf(const std::vector<apex::Option<V>>& options, V value) {
  for (const auto& o : options)
    if (o.value == value) return o.name;
  return "?";  // not reached: each value is in its table
}

/** As cv::Algorithm::load<T> does, from the node: none if it holds no trained model. */
template <class T>
cv::Ptr<cv::ml::StatModel> readModel(const cv::FileNode& node) {
  cv::Ptr<T> model = T::create();
  model->read(node);
  return model->isTrained() ? cv::Ptr<cv::ml::StatModel>(model) : cv::Ptr<cv::ml::StatModel>();
}

}  // namespace

// In functions: FeatureExtract's parameter declarations read them during static initialisation.
const std::vector<apex::Option<FeatureMethod>>& featureMethods() {
  static const std::vector<apex::Option<FeatureMethod>> methods{{"hog", FeatureMethod::kHog},
                                                                {"color_histogram", FeatureMethod::kColorHistogram},
                                                                {"hu_moments", FeatureMethod::kHuMoments},
                                                                {"raw_pixels", FeatureMethod::kRawPixels}};
  return methods;
}

const std::vector<apex::Option<ColorSpace>>& colorSpaces() {
  static const std::vector<apex::Option<ColorSpace>> spaces{{"hsv", ColorSpace::kHsv}, {"bgr", ColorSpace::kBgr}};
  return spaces;
}

int featureLength(const FeatureSettings& s) {
  const auto need = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
  };
  if (s.method == FeatureMethod::kHog) {
    need(s.cells >= 2 && s.cells <= 16, "hog needs 2 to 16 cells per side, not " + std::to_string(s.cells));
    need(s.size >= 2 * s.cells && s.size <= 512 && s.size % s.cells == 0, "hog needs a size that is a multiple of cells (" +
                                                                              std::to_string(s.cells) + "), up to 512, not " +
                                                                              std::to_string(s.size));
    need(s.bins >= 2 && s.bins <= 64, "hog needs 2 to 64 bins, not " + std::to_string(s.bins));
    return (s.cells - 1) * (s.cells - 1) * 4 * s.bins;
  }
  if (s.method == FeatureMethod::kColorHistogram) {
    need(s.bins >= 2 && s.bins <= 64, "color_histogram needs 2 to 64 bins, not " + std::to_string(s.bins));
    return 3 * s.bins;
  }
  if (s.method == FeatureMethod::kHuMoments) return 7;
  need(s.size >= 2 && s.size <= 512, "raw_pixels needs a size of 2 to 512, not " + std::to_string(s.size));
  return s.size * s.size;
}

std::string featureSummary(const FeatureSettings& s) {
  const auto n = [](int v) { return std::to_string(v); };
  const std::string method = nameOf(featureMethods(), s.method);
  if (s.method == FeatureMethod::kHog)
    return method + " size=" + n(s.size) + " cells=" + n(s.cells) + " bins=" + n(s.bins) + " deskew=" + n(s.deskew);
  if (s.method == FeatureMethod::kColorHistogram)
    return method + " bins=" + n(s.bins) + " space=" + nameOf(colorSpaces(), s.space);
  if (s.method == FeatureMethod::kHuMoments) return method + " binary=" + n(s.binary);
  return method + " size=" + n(s.size) + " deskew=" + n(s.deskew);
}

cv::Mat featureRow(const cv::Mat& crop, const FeatureSettings& s) {
  featureLength(s);  // the settings fit
  if (crop.empty()) throw std::invalid_argument("cannot take features from an empty region");
  if (s.method == FeatureMethod::kHog) return hog(crop, s);
  if (s.method == FeatureMethod::kColorHistogram) return colorHistogram(crop, s);
  if (s.method == FeatureMethod::kHuMoments) return huMoments(crop, s);
  return rawPixels(crop, s);
}

// ---------------------------------------------------------------- LearnedModel

LearnedModel LearnedModel::load(const std::string& path) {
  const auto bad = [&](const std::string& what) { return std::invalid_argument("the model '" + path + "' " + what); };
  std::ifstream file(path);
  if (!file) throw bad("cannot be read: no such file, or not readable");
  if (file.peek() == std::ifstream::traits_type::eof()) throw bad("is empty");
  file.close();
  try {
    cv::FileStorage fs(path, cv::FileStorage::READ);
    if (!fs.isOpened()) throw bad("cannot be read (not a model file?)");
    return read(fs, path);
  } catch (const cv::Exception& e) {
    throw bad("is damaged: " + e.err);  // e.g. a file cut short, or not YAML, XML or JSON at all
  }
}

LearnedModel LearnedModel::parse(const std::string& text, const std::string& name) {
  try {
    cv::FileStorage fs(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
    if (!fs.isOpened()) throw std::invalid_argument("the model '" + name + "' cannot be read");
    return read(fs, name);
  } catch (const cv::Exception& e) {
    throw std::invalid_argument("the model '" + name + "' is damaged: " + e.err);
  }
}

LearnedModel LearnedModel::read(cv::FileStorage& fs, const std::string& name) {
  const auto bad = [&](const std::string& what) { return std::invalid_argument("the model '" + name + "' " + what); };
  const cv::FileNode node = fs.getFirstTopLevelNode();
  if (node.empty() || node.name().empty()) throw bad("is empty, or not a model file");
  LearnedModel m;
  const std::string top = node.name();
  for (const Kind& k : kKinds)
    if (top == k.node) m.kind_ = k.kind;
  if (m.kind_.empty()) {
    std::string known;
    for (const Kind& k : kKinds) known += std::string(known.empty() ? "" : ", ") + k.node;
    throw bad("is not a model Classifier knows: its first node is '" + top + "' (knows " + known + ")");
  }
  if (m.kind_ == "svm") m.model_ = readModel<cv::ml::SVM>(node);
  else if (m.kind_ == "rtrees") m.model_ = readModel<cv::ml::RTrees>(node);
  else if (m.kind_ == "knn") m.model_ = readModel<cv::ml::KNearest>(node);
  else if (m.kind_ == "mlp") m.model_ = readModel<cv::ml::ANN_MLP>(node);
  else if (m.kind_ == "boost") m.model_ = readModel<cv::ml::Boost>(node);
  else if (m.kind_ == "dtrees") m.model_ = readModel<cv::ml::DTrees>(node);
  else if (m.kind_ == "lr") m.model_ = readModel<cv::ml::LogisticRegression>(node);
  else m.model_ = readModel<cv::ml::NormalBayesClassifier>(node);
  if (!m.model_) throw bad("is damaged: its " + top + " holds no trained model");

  if (m.kind_ == "mlp") {
    const cv::Mat layers = m.model_.dynamicCast<cv::ml::ANN_MLP>()->getLayerSizes();
    // a file cut short after the sizes still reads, with weights of zero
    if (layers.total() < 2 || node["weights"].size() + 1 != layers.total()) throw bad("is damaged: its network lacks weights");
    m.var_count_ = layers.at<int>(0);
  } else if (m.kind_ == "lr") {
    m.var_count_ = m.model_.dynamicCast<cv::ml::LogisticRegression>()->get_learnt_thetas().cols - 1;  // the first: the bias
  } else {
    m.var_count_ = m.model_->getVarCount();
  }
  if (m.kind_ == "svm") {
    const int type = m.model_.dynamicCast<cv::ml::SVM>()->getType();
    cv::Mat classes;
    if (type == cv::ml::SVM::C_SVC || type == cv::ml::SVM::NU_SVC) node["class_labels"] >> classes;
    m.svm_classes_ = static_cast<int>(classes.total());
  }
  const cv::FileNode features = fs["apex_features"];
  if (features.isString()) m.features_ = static_cast<std::string>(features);
  return m;
}

std::vector<Prediction> LearnedModel::predict(const cv::Mat& rows) const {
  std::vector<Prediction> out(rows.rows);
  if (rows.empty()) return out;
  cv::Mat results;
  if (kind_ == "mlp") {
    model_->predict(rows, results);
    for (int i = 0; i < results.rows; ++i) {
      const float* o = results.ptr<float>(i);
      const int best = static_cast<int>(std::max_element(o, o + results.cols) - o);
      double sum = 0;
      for (int j = 0; j < results.cols; ++j) sum += std::exp(kMlpSharpness * (o[j] - o[best]));
      out[i] = {best, 1.0 / sum};
    }
    return out;
  }
  if (kind_ == "knn") {
    const auto knn = model_.dynamicCast<cv::ml::KNearest>();
    const int k = knn->getDefaultK();
    cv::Mat neighbours;
    knn->findNearest(rows, k, results, neighbours);
    for (int i = 0; i < rows.rows; ++i) {
      const float label = results.at<float>(i);
      int agree = 0;
      for (int j = 0; j < neighbours.cols; ++j) agree += neighbours.at<float>(i, j) == label;
      out[i] = {cvRound(label), neighbours.cols ? static_cast<double>(agree) / neighbours.cols : 1.0};
    }
    return out;
  }
  model_->predict(rows, results);
  results.convertTo(results, CV_32F);  // lr and nbayes give CV_32S
  for (int i = 0; i < rows.rows; ++i) out[i] = {cvRound(results.at<float>(i)), 1.0};
  if (kind_ == "svm" && svm_classes_ == 2) {
    cv::Mat raw;
    model_->predict(rows, raw, cv::ml::StatModel::RAW_OUTPUT);
    for (int i = 0; i < rows.rows; ++i) out[i].confidence = 1.0 / (1.0 + std::exp(-2.0 * std::abs(raw.at<float>(i))));
  } else if (kind_ == "rtrees") {
    cv::Mat votes;  // a row of the classes' labels, then a row of votes per sample
    model_.dynamicCast<cv::ml::RTrees>()->getVotes(rows, votes, 0);
    votes.convertTo(votes, CV_64F);
    for (int i = 0; i < rows.rows; ++i) {
      const double all = cv::sum(votes.row(i + 1))[0];
      for (int c = 0; c < votes.cols; ++c)
        if (cvRound(votes.at<double>(0, c)) == out[i].label) out[i].confidence = all > 0 ? votes.at<double>(i + 1, c) / all : 0;
    }
  }
  return out;
}

}  // namespace apex_nodes
