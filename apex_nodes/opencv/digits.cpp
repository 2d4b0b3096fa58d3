// Digit features and the digit MLP (see apex_nodes/digits.hpp).
#include "apex_nodes/digits.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>

#include "apex/core/graph_file.hpp"

namespace apex_nodes {
namespace {

constexpr int kFormat = 1;  // the model file's version
constexpr double kSharpness = 10;
// RPROP's first weight steps. Its default, 0.1, is too big for a few hundred inputs: the network
// saturates and stalls near 60% on the demo's samples; 0.01 learns them all. A batch that goes on
// from the last starts smaller still, or its first steps undo what the last batch learned.
constexpr double kRpropStart = 0.01, kRpropResume = 1e-3;  // softmax temperature: outputs are trained towards 0 and 1

cv::Mat toGray8(const cv::Mat& crop) {
  cv::Mat gray;
  switch (crop.channels()) {
    case 1:
      gray = crop;
      break;
    case 3:
      cv::cvtColor(crop, gray, cv::COLOR_BGR2GRAY);
      break;
    case 4:
      cv::cvtColor(crop, gray, cv::COLOR_BGRA2GRAY);
      break;
    default:
      throw std::invalid_argument("cannot take digits from " + std::to_string(crop.channels()) + "-channel crops");
  }
  if (gray.depth() != CV_8U) cv::normalize(gray, gray, 0, 255, cv::NORM_MINMAX, CV_8U);
  return gray;
}

/** Where `light` is set, the components that do not touch the border, at least `min_area` big. */
cv::Mat inner(const cv::Mat& light, int min_area) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(light, labels, stats, centroids, 8, CV_32S);
  std::vector<uchar> keep(n, 0);
  for (int i = 1; i < n; ++i) {
    const int x = stats.at<int>(i, cv::CC_STAT_LEFT), y = stats.at<int>(i, cv::CC_STAT_TOP);
    const int w = stats.at<int>(i, cv::CC_STAT_WIDTH), h = stats.at<int>(i, cv::CC_STAT_HEIGHT);
    const bool edge = x == 0 || y == 0 || x + w == light.cols || y + h == light.rows;
    keep[i] = !edge && stats.at<int>(i, cv::CC_STAT_AREA) >= min_area ? 255 : 0;
  }
  cv::Mat mask(light.size(), CV_8U);
  for (int y = 0; y < light.rows; ++y)
    for (int x = 0; x < light.cols; ++x) mask.at<uchar>(y, x) = keep[labels.at<int>(y, x)];
  return mask;
}

/** The digit's pixels (white) in a crop of a dark sign with a light digit: the light parts that do
 *  not touch the crop's border. A crop with light scene around the sign (its border mostly light)
 *  is first cut to the sign, the largest dark part inside. */
cv::Mat digitMask(const cv::Mat& gray, bool cut = true) {
  cv::Mat light;
  cv::threshold(gray, light, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
  const int min_area = std::max(4, gray.rows * gray.cols / 400);  // specks of noise
  const int border = cv::countNonZero(light.row(0)) + cv::countNonZero(light.row(light.rows - 1)) +
                     cv::countNonZero(light.col(0)) + cv::countNonZero(light.col(light.cols - 1));
  if (cut && border > light.rows + light.cols) {
    const cv::Rect sign = cv::boundingRect(inner(255 - light, gray.rows * gray.cols / 4));
    if (!sign.empty()) {
      cv::Mat mask(gray.size(), CV_8U, cv::Scalar(0));
      digitMask(gray(sign), false).copyTo(mask(sign));
      return mask;
    }
  }
  return inner(light, min_area);
}

int argmax(const float* v, int n) { return static_cast<int>(std::max_element(v, v + n) - v); }

}  // namespace

cv::Mat digitFeatures(const cv::Mat& crop, const DigitFeatureSettings& s) {
  if (crop.empty()) throw std::invalid_argument("cannot take digits from an empty crop");
  const cv::Mat mask = digitMask(toGray8(crop));
  cv::Mat square(s.size, s.size, CV_8U, cv::Scalar(0));
  const cv::Rect box = cv::boundingRect(mask);
  if (!box.empty()) {
    const double f = static_cast<double>(s.size) / std::max(box.width, box.height);
    const cv::Size scaled(std::max(1, cvRound(box.width * f)), std::max(1, cvRound(box.height * f)));
    cv::Mat digit;
    cv::resize(mask(box), digit, scaled, 0, 0, cv::INTER_AREA);
    digit.copyTo(square(cv::Rect((s.size - scaled.width) / 2, (s.size - scaled.height) / 2, scaled.width, scaled.height)));
  }
  cv::GaussianBlur(square, square, cv::Size(3, 3), 0);  // a stroke a pixel off still overlaps
  cv::Mat row;
  square.reshape(1, 1).convertTo(row, CV_32F, 1.0 / 255);
  return row;
}

cv::Mat digitFeatures(const std::vector<cv::Mat>& crops, const DigitFeatureSettings& settings) {
  cv::Mat rows;
  for (const auto& c : crops) rows.push_back(digitFeatures(c, settings));
  return rows;
}

namespace {

/** The crop slanted, turned and scaled a little at random, its edges extended (the sign stays around). */
cv::Mat varied(const cv::Mat& crop, std::mt19937& rng) {
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const cv::Point2f centre(crop.cols / 2.f, crop.rows / 2.f);
  cv::Mat warp = cv::getRotationMatrix2D(centre, uniform(-6, 6), uniform(0.9, 1.1));
  const double shear = uniform(-0.15, 0.15);
  warp.at<double>(0, 1) += shear;
  warp.at<double>(0, 2) -= shear * centre.y;
  cv::Mat out;
  cv::warpAffine(crop, out, warp, crop.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return out;
}

}  // namespace

DigitModel DigitModel::train(const std::vector<cv::Mat>& crops, const std::vector<int>& labels,
                             const DigitFeatureSettings& features, const TrainSettings& settings,
                             const std::function<void(const TrainProgress&)>& progress) {
  if (crops.size() != labels.size() || crops.empty())
    throw std::invalid_argument("needs one label per crop (" + std::to_string(crops.size()) + " crops, " +
                                std::to_string(labels.size()) + " labels)");
  DigitModel m;
  m.features_ = features;
  m.classes_ = labels;
  std::sort(m.classes_.begin(), m.classes_.end());
  m.classes_.erase(std::unique(m.classes_.begin(), m.classes_.end()), m.classes_.end());
  if (m.classes_.size() < 2) throw std::invalid_argument("needs samples of at least two classes");

  std::vector<int> order(labels.size());
  std::iota(order.begin(), order.end(), 0);
  std::mt19937 rng(settings.seed);
  std::shuffle(order.begin(), order.end(), rng);
  const int held = static_cast<int>(std::lround(settings.validation * order.size()));
  if (settings.validation > 0 && (held < 1 || static_cast<int>(order.size()) - held < static_cast<int>(m.classes_.size())))
    throw std::invalid_argument("too few samples (" + std::to_string(order.size()) + ") to hold " +
                                std::to_string(settings.validation) + " of them out for validation");
  cv::Mat train_x, val_x, train_y;
  std::vector<int> train_labels, val_labels;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const int k = order[i];
    if (static_cast<int>(i) < held) {
      val_x.push_back(digitFeatures(crops[k], features));
      val_labels.push_back(labels[k]);
      continue;
    }
    cv::Mat target(1, static_cast<int>(m.classes_.size()), CV_32F, cv::Scalar(0));
    target.at<float>(std::lower_bound(m.classes_.begin(), m.classes_.end(), labels[k]) - m.classes_.begin()) = 1;
    for (int copy = 0; copy <= std::max(0, settings.augment); ++copy) {
      train_x.push_back(digitFeatures(copy ? varied(crops[k], rng) : crops[k], features));
      train_labels.push_back(labels[k]);
      train_y.push_back(target);
    }
  }

  std::vector<int> layers{train_x.cols};
  layers.insert(layers.end(), settings.hidden.begin(), settings.hidden.end());
  layers.push_back(static_cast<int>(m.classes_.size()));
  m.mlp_ = cv::ml::ANN_MLP::create();
  m.mlp_->setLayerSizes(layers);
  m.mlp_->setActivationFunction(cv::ml::ANN_MLP::SIGMOID_SYM, 1, 1);
  m.mlp_->setTrainMethod(cv::ml::ANN_MLP::RPROP);
  m.mlp_->setRpropDW0(kRpropStart);
  cv::theRNG().state = settings.seed;  // the initial weights
  const auto data = cv::ml::TrainData::create(train_x, cv::ml::ROW_SAMPLE, train_y);
  for (int done = 0; done < settings.epochs;) {
    const int n = std::min(std::max(1, settings.batch), settings.epochs - done);
    m.mlp_->setTermCriteria(cv::TermCriteria(cv::TermCriteria::MAX_ITER, n, 0));
    m.mlp_->train(data, done ? cv::ml::ANN_MLP::UPDATE_WEIGHTS : 0);
    m.mlp_->setRpropDW0(kRpropResume);  // later batches go on where this one stopped, with small first steps
    done += n;
    m.validation_accuracy_ = val_x.empty() ? 0 : m.accuracy(val_x, val_labels);
    if (progress) progress({done, m.accuracy(train_x, train_labels), m.validation_accuracy_});
  }
  return m;
}

bool DigitModel::fits() const {
  const cv::Mat layers = mlp_->getLayerSizes();
  const int n = static_cast<int>(layers.total());
  if (features_.size < 2 || features_.size > 256 || n < 2 || classes_.size() < 2 || !mlp_->isTrained() ||
      layers.at<int>(0) != features_.size * features_.size || layers.at<int>(n - 1) != static_cast<int>(classes_.size()))
    return false;
  for (int i = 1; i < n; ++i) {
    const cv::Mat w = mlp_->getWeights(i);
    if (w.rows != layers.at<int>(i - 1) + 1 || w.cols != layers.at<int>(i) || !cv::checkRange(w)) return false;
  }
  return true;
}

DigitPrediction DigitModel::predict(const cv::Mat& features) const {
  cv::Mat out;
  mlp_->predict(features, out);
  const float* o = out.ptr<float>(0);
  const int n = out.cols, best = argmax(o, n);
  double sum = 0;
  for (int i = 0; i < n; ++i) sum += std::exp(kSharpness * (o[i] - o[best]));
  return {classes_[best], 1.0 / sum};
}

double DigitModel::accuracy(const std::vector<cv::Mat>& crops, const std::vector<int>& labels) const {
  return accuracy(digitFeatures(crops, features_), labels);
}

double DigitModel::accuracy(const cv::Mat& samples, const std::vector<int>& labels) const {
  if (samples.empty()) return 0;
  cv::Mat out;
  mlp_->predict(samples, out);
  int right = 0;
  for (int i = 0; i < out.rows; ++i) right += classes_[argmax(out.ptr<float>(i), out.cols)] == labels[i];
  return static_cast<double>(right) / out.rows;
}

void DigitModel::save(const std::string& path) const {
  cv::FileStorage fs(".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  fs << "apex_digit_model" << kFormat;
  fs << "feature_size" << features_.size;
  fs << "classes" << classes_;
  fs << "validation_accuracy" << validation_accuracy_;
  fs << "mlp"
     << "{";
  mlp_->write(fs);
  fs << "}";
  const apex::Status st = apex::writeFileAtomically(path, fs.releaseAndGetString());
  if (!st) throw std::runtime_error(st.message());
}

DigitModel DigitModel::load(const std::string& path) {
  const auto bad = [&](const std::string& what) { return std::invalid_argument("the model '" + path + "' " + what); };
  DigitModel m;
  try {
    cv::FileStorage fs(path, cv::FileStorage::READ | cv::FileStorage::FORMAT_YAML);
    if (!fs.isOpened()) throw bad("cannot be read (no such file, or not a model file)");
    if (fs["apex_digit_model"].empty()) throw bad("is not an APEX digit model (apex_train_mlp writes them)");
    if (static_cast<int>(fs["apex_digit_model"]) != kFormat) throw bad("has an unknown format version");
    m.features_.size = static_cast<int>(fs["feature_size"]);
    fs["classes"] >> m.classes_;
    m.validation_accuracy_ = static_cast<double>(fs["validation_accuracy"]);
    m.mlp_ = cv::ml::ANN_MLP::create();
    m.mlp_->read(fs["mlp"]);
    // The network's weights are there, one matrix per layer after the first: a file cut short
    // after its sizes still reads, with weights of zero.
    if (fs["mlp"]["weights"].size() + 1 != m.mlp_->getLayerSizes().total())
      throw bad("is damaged: it lacks weights (cut short?)");
  } catch (const cv::Exception& e) {
    throw bad("is damaged: " + e.err);  // e.g. a file cut short
  }
  if (!m.fits()) throw bad("is damaged: its network does not fit its feature size and classes, or lacks weights");
  return m;
}

}  // namespace apex_nodes
