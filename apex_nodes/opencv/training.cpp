// Training a classifier for Classifier (see apex_nodes/training.hpp): apex_train's work.
#include "apex_nodes/training.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>

#include "apex/core/graph_file.hpp"

namespace apex_nodes {
namespace {

// RPROP's first weight steps, as DigitModel's (digits.cpp): its default, 0.1, saturates the network.
constexpr double kRpropStart = 0.01;

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

bool number(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  return *end == '\0' && errno == 0 && std::isfinite(value);
}

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/** `n` indices shuffled by `seed`: Fisher-Yates on mt19937, the same on every platform. */
std::vector<int> shuffled(int n, unsigned seed) {
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::mt19937 rng(seed);
  for (int i = n - 1; i > 0; --i) std::swap(order[i], order[rng() % static_cast<unsigned>(i + 1)]);
  return order;
}

cv::Ptr<cv::ml::StatModel> train(const std::string& kind, const ModelOptions& o, const cv::Mat& x, const std::vector<int>& y) {
  const cv::Mat labels = cv::Mat(y, true);  // CV_32S: a categorical response (classes, not a regression)
  if (kind == "svm") {
    auto svm = cv::ml::SVM::create();
    svm->setType(cv::ml::SVM::C_SVC);
    svm->setKernel(cv::ml::SVM::RBF);
    svm->setC(o.svm_c);
    svm->setGamma(o.svm_gamma);
    svm->train(cv::ml::TrainData::create(x, cv::ml::ROW_SAMPLE, labels));
    return svm;
  }
  if (kind == "rtrees") {
    auto trees = cv::ml::RTrees::create();
    trees->setMaxDepth(16);
    trees->setMinSampleCount(2);
    trees->setTermCriteria(cv::TermCriteria(cv::TermCriteria::MAX_ITER, o.trees, 0));
    trees->train(cv::ml::TrainData::create(x, cv::ml::ROW_SAMPLE, labels));
    return trees;
  }
  if (kind == "boost") {
    auto boost = cv::ml::Boost::create();
    boost->setWeakCount(o.trees);
    boost->train(cv::ml::TrainData::create(x, cv::ml::ROW_SAMPLE, labels));
    return boost;
  }
  if (kind == "knn") {
    auto knn = cv::ml::KNearest::create();
    knn->setDefaultK(o.k);
    knn->setIsClassifier(true);
    cv::Mat responses;
    labels.convertTo(responses, CV_32F);
    knn->train(cv::ml::TrainData::create(x, cv::ml::ROW_SAMPLE, responses));
    return knn;
  }
  // mlp: an output per label 0..the largest, trained towards 1 for the sample's and 0 for the rest
  const int outputs = *std::max_element(y.begin(), y.end()) + 1;
  cv::Mat targets = cv::Mat::zeros(x.rows, outputs, CV_32F);
  for (int i = 0; i < x.rows; ++i) targets.at<float>(i, y[i]) = 1;
  std::vector<int> layers{x.cols};
  layers.insert(layers.end(), o.hidden.begin(), o.hidden.end());
  layers.push_back(outputs);
  auto mlp = cv::ml::ANN_MLP::create();
  mlp->setLayerSizes(layers);
  mlp->setActivationFunction(cv::ml::ANN_MLP::SIGMOID_SYM, 1, 1);
  mlp->setTrainMethod(cv::ml::ANN_MLP::RPROP);
  mlp->setRpropDW0(kRpropStart);
  mlp->setTermCriteria(cv::TermCriteria(cv::TermCriteria::MAX_ITER, o.epochs, 0));
  cv::theRNG().state = o.seed;  // the initial weights
  mlp->train(cv::ml::TrainData::create(x, cv::ml::ROW_SAMPLE, targets));
  return mlp;
}

}  // namespace

Samples readCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("cannot read '" + path + "'");
  Samples s;
  std::vector<float> values;
  int width = -1, width_line = 0;
  bool first = true;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    line = trimmed(line);
    if (line.empty()) continue;
    std::vector<std::string> fields;
    std::stringstream split(line);
    for (std::string f; std::getline(split, f, ',');) fields.push_back(trimmed(f));
    if (line.back() == ',') fields.emplace_back();
    double value = 0;
    if (first && !number(fields[0], value)) {  // a header
      first = false;
      continue;
    }
    first = false;
    const std::string where = path + " line " + std::to_string(n) + ": ";
    if (fields.size() < 2) throw std::invalid_argument(where + "needs a label and at least one feature");
    if (!number(fields[0], value) || value < 0 || value != std::floor(value) || value > 1e9)
      throw std::invalid_argument(where + "the label '" + fields[0] + "' is not a whole number >= 0");
    s.labels.push_back(static_cast<int>(value));
    const int features = static_cast<int>(fields.size()) - 1;
    if (width < 0) width = features, width_line = n;
    if (features != width)
      throw std::invalid_argument(where + "has " + std::to_string(features) + " features, line " + std::to_string(width_line) +
                                  " has " + std::to_string(width));
    for (int i = 1; i <= features; ++i) {
      if (!number(fields[i], value) || std::abs(value) > 3e38)
        throw std::invalid_argument(where + "feature " + std::to_string(i) + " ('" + fields[i] + "') is not a number");
      values.push_back(static_cast<float>(value));
    }
  }
  if (s.labels.empty()) throw std::invalid_argument("'" + path + "' lists no samples (lines of label,feature,...)");
  s.rows = cv::Mat(static_cast<int>(s.labels.size()), width, CV_32F, values.data()).clone();
  return s;
}

Samples featuresOf(const std::vector<cv::Mat>& crops, const std::vector<int>& labels, const FeatureSettings& settings) {
  if (crops.size() != labels.size())
    throw std::invalid_argument("needs one label per crop (" + std::to_string(crops.size()) + " crops, " +
                                std::to_string(labels.size()) + " labels)");
  Samples s;
  s.labels = labels;
  s.rows = cv::Mat(0, featureLength(settings), CV_32F);
  for (const auto& c : crops) s.rows.push_back(featureRow(c, settings));
  return s;
}

TrainResult trainModel(const Samples& samples, const ModelOptions& o, const std::string& features) {
  const int n = samples.rows.rows;
  if (n == 0 || static_cast<std::size_t>(n) != samples.labels.size() || samples.rows.type() != CV_32F)
    throw std::invalid_argument("needs a float row of features per label (" + std::to_string(n) + " rows, " +
                                std::to_string(samples.labels.size()) + " labels)");
  const std::vector<std::string> kinds{"svm", "rtrees", "knn", "mlp", "boost"};
  if (std::find(kinds.begin(), kinds.end(), o.model) == kinds.end())
    throw std::invalid_argument("unknown model '" + o.model + "' (svm, rtrees, knn, mlp or boost)");
  if (!(o.validation >= 0 && o.validation <= 0.9))
    throw std::invalid_argument("the validation share must be from 0 to 0.9, not " + std::to_string(o.validation));
  TrainResult r;
  r.kind = o.model;
  r.features = features;
  r.classes = samples.labels;
  std::sort(r.classes.begin(), r.classes.end());
  r.classes.erase(std::unique(r.classes.begin(), r.classes.end()), r.classes.end());
  if (r.classes.front() < 0)
    throw std::invalid_argument("labels must be >= 0 (a region's -1 means none), not " + std::to_string(r.classes.front()));
  if (r.classes.size() < 2) throw std::invalid_argument("needs samples of at least two classes");
  if (o.model == "boost" && r.classes.size() != 2)
    throw std::invalid_argument("boost tells two classes apart, these samples have " + std::to_string(r.classes.size()));
  if (o.model == "mlp" && r.classes.back() > 1000)
    throw std::invalid_argument("mlp needs labels up to 1000 (an output each), not " + std::to_string(r.classes.back()));

  const std::vector<int> order = shuffled(n, o.seed);
  const int held = static_cast<int>(std::lround(o.validation * n));
  if (o.validation > 0 && held < 1)
    throw std::invalid_argument("too few samples (" + std::to_string(n) + ") to hold " + std::to_string(o.validation) +
                                " of them out for validation");
  cv::Mat train_x(0, samples.rows.cols, CV_32F), val_x(0, samples.rows.cols, CV_32F);
  std::vector<int> train_y, val_y;
  for (int i = 0; i < n; ++i) {
    const int k = order[i];
    (i < held ? val_x : train_x).push_back(samples.rows.row(k));
    (i < held ? val_y : train_y).push_back(samples.labels[k]);
  }
  if (std::set<int>(train_y.begin(), train_y.end()).size() < 2)
    throw std::invalid_argument("the samples not held out (" + std::to_string(train_y.size()) +
                                ") are of one class: hold fewer out");
  if (o.model == "knn" && (o.k < 1 || o.k > static_cast<int>(train_y.size())))
    throw std::invalid_argument("knn needs k from 1 to the training samples (" + std::to_string(train_y.size()) + "), not " +
                                std::to_string(o.k));
  r.train_samples = static_cast<int>(train_y.size());
  r.validation_samples = held;
  try {
    r.model = train(o.model, o, train_x, train_y);
  } catch (const cv::Exception& e) {
    throw std::runtime_error("training the " + o.model + " failed: " + e.err);
  }
  if (!r.model || !r.model->isTrained()) throw std::runtime_error("training the " + o.model + " failed");

  // The held-out samples as Classifier labels them: the model read back from its file's text.
  const std::size_t c = r.classes.size();
  r.confusion.assign(c, std::vector<int>(c + 1, 0));
  if (held == 0) return r;
  const LearnedModel read = LearnedModel::parse(r.text(), "(the trained " + o.model + ")");
  const std::vector<Prediction> predicted = read.predict(val_x);
  int right = 0;
  for (int i = 0; i < held; ++i) {
    const auto truth = std::lower_bound(r.classes.begin(), r.classes.end(), val_y[i]) - r.classes.begin();
    const auto label = std::lower_bound(r.classes.begin(), r.classes.end(), predicted[i].label);
    const bool known = label != r.classes.end() && *label == predicted[i].label;
    ++r.confusion[truth][known ? label - r.classes.begin() : c];
    right += predicted[i].label == val_y[i];
  }
  r.validation_accuracy = static_cast<double>(right) / held;
  return r;
}

std::string TrainResult::confusionTable() const {
  std::string out = "true\\label";
  char cell[32];
  for (int label : classes) {
    std::snprintf(cell, sizeof cell, " %5d", label);
    out += cell;
  }
  out += "  other";
  for (std::size_t t = 0; t < confusion.size(); ++t) {
    std::snprintf(cell, sizeof cell, "\n%10d", classes[t]);
    out += cell;
    for (std::size_t p = 0; p < confusion[t].size(); ++p) {
      std::snprintf(cell, sizeof cell, p + 1 < confusion[t].size() ? " %5d" : " %6d", confusion[t][p]);
      out += cell;
    }
  }
  return out + "\n";
}

std::string TrainResult::text(const std::string& path) const {
  if (!model) throw std::runtime_error("no trained model to write");
  const std::string format = endsWith(path, ".xml") ? ".xml" : endsWith(path, ".json") ? ".json" : ".yaml";
  cv::FileStorage fs(format, cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  fs << model->getDefaultName() << "{";  // as cv::Algorithm::save writes it
  model->write(fs);
  fs << "}";
  if (!features.empty()) fs << "apex_features" << features;
  return fs.releaseAndGetString();
}

void TrainResult::save(const std::string& path) const {
  if (endsWith(path, ".gz")) throw std::runtime_error("cannot write '" + path + "': compressed model files are not written");
  const apex::Status st = apex::writeFileAtomically(path, text(path));
  if (!st) throw std::runtime_error(st.message());
}

}  // namespace apex_nodes
