// Trains a model for Classifier (any of OpenCV's svm, rtrees, knn, mlp, boost):
//   apex_train INPUT MODEL.yaml [--model svm|rtrees|knn|mlp|boost] [--validation F] [--seed N]
//              [--svm-c C] [--svm-gamma G] [--k N] [--trees N] [--hidden N[,N...]] [--epochs N]
//              [--features METHOD] [--size N] [--cells N] [--bins N] [--deskew] [--space hsv|bgr] [--hu-gray]
// INPUT is SampleExport's folder (index.csv and its crops: their features computed as FeatureExtract
// computes them, with --features and its settings, which the model records so that Classifier can
// check them) or a CSV file of samples ("label,feature,feature,..." a line). Holds a share out
// (--validation, shuffled by --seed), trains on the rest, prints the validation accuracy and the
// confusion matrix, and writes the model (atomically). apex_train_mlp remains DigitClassifier's.
#include <sys/stat.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "apex_nodes/training.hpp"
#include "cli.hpp"
#include "samples.hpp"

namespace {

struct Options {
  std::string input, model;
  apex_nodes::ModelOptions train;
  apex_nodes::FeatureSettings features;
};

const char* kUsage =
    "usage: apex_train INPUT MODEL.yaml [--model svm|rtrees|knn|mlp|boost] [--validation F] [--seed N]\n"
    "         [--svm-c C] [--svm-gamma G] [--k N] [--trees N] [--hidden N[,N...]] [--epochs N]\n"
    "         [--features hog|color_histogram|hu_moments|raw_pixels] [--size N] [--cells N] [--bins N] [--deskew]\n"
    "         [--space hsv|bgr] [--hu-gray]\n"
    "  INPUT: SampleExport's folder (features of its crops, as FeatureExtract computes them) or a CSV file\n"
    "  of lines 'label,feature,feature,...'";

/** The value of the option named `text`; refused with the names when none is. */
template <class V>
V named(const std::string& what, const std::string& text, const std::vector<apex::Option<V>>& options) {
  std::string names;
  for (const auto& o : options) {
    if (text == o.name) return o.value;
    names += (names.empty() ? "" : ", ") + std::string(o.name);
  }
  throw std::invalid_argument(what + " needs one of " + names + ", not '" + text + "'");
}

int whole(const std::string& what, const std::string& text, int lo, int hi) {
  return static_cast<int>(apex_tools::number(what, text, lo, hi));
}

double real(const std::string& what, const std::string& text, double lo, double hi) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end || !(v >= lo && v <= hi))
    throw std::invalid_argument(what + " needs a number from " + std::to_string(lo) + " to " + std::to_string(hi) + ", not '" +
                                text + "'");
  return v;
}

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> plain;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0) {
      plain.push_back(arg);
      continue;
    }
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage << "\n";
      std::exit(0);
    }
    if (arg == "--deskew") {  // flags: no value
      o.features.deskew = true;
      continue;
    }
    if (arg == "--hu-gray") {
      o.features.binary = false;
      continue;
    }
    if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
    const std::string value = argv[++i];
    if (arg == "--model") {
      o.train.model = value;
    } else if (arg == "--validation") {
      o.train.validation = real(arg, value, 0, 0.9);
    } else if (arg == "--seed") {
      o.train.seed = static_cast<unsigned>(whole(arg, value, 0, 1 << 30));
    } else if (arg == "--svm-c") {
      o.train.svm_c = real(arg, value, 1e-6, 1e6);
    } else if (arg == "--svm-gamma") {
      o.train.svm_gamma = real(arg, value, 1e-9, 1e6);
    } else if (arg == "--k") {
      o.train.k = whole(arg, value, 1, 1000);
    } else if (arg == "--trees") {
      o.train.trees = whole(arg, value, 1, 10000);
    } else if (arg == "--hidden") {
      o.train.hidden.clear();
      std::stringstream list(value);
      for (std::string n; std::getline(list, n, ',');) o.train.hidden.push_back(whole("--hidden", n, 1, 4096));
    } else if (arg == "--epochs") {
      o.train.epochs = whole(arg, value, 1, 100000);
    } else if (arg == "--features") {
      o.features.method = named(arg, value, apex_nodes::featureMethods());
    } else if (arg == "--size") {
      o.features.size = whole(arg, value, 2, 512);
    } else if (arg == "--cells") {
      o.features.cells = whole(arg, value, 2, 16);
    } else if (arg == "--bins") {
      o.features.bins = whole(arg, value, 2, 64);
    } else if (arg == "--space") {
      o.features.space = named(arg, value, apex_nodes::colorSpaces());
    } else {
      throw std::invalid_argument("unknown option '" + arg + "'");
    }
  }
  if (plain.size() != 2) throw std::invalid_argument("needs INPUT and MODEL.yaml");
  o.input = plain[0], o.model = plain[1];
  return o;
}

bool isFolder(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    o = parse(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "apex_train: " << e.what() << "\n" << kUsage << "\n";
    return 2;
  }
  try {
    apex_nodes::Samples samples;
    std::string features;  // recorded with the model: Classifier compares it with FeatureExtract's
    if (isFolder(o.input)) {
      std::vector<cv::Mat> crops;
      std::vector<int> labels;
      apex_tools::readSamples(o.input, cv::IMREAD_COLOR, crops, labels);
      samples = apex_nodes::featuresOf(crops, labels, o.features);
      features = apex_nodes::featureSummary(o.features);
    } else {
      samples = apex_nodes::readCsv(o.input);
    }
    std::printf("apex_train: %d samples of %d features from %s%s, %.0f%% held out for validation (seed %u)\n", samples.rows.rows,
                samples.rows.cols, o.input.c_str(), features.empty() ? "" : (" (" + features + ")").c_str(),
                100 * o.train.validation, o.train.seed);
    std::fflush(stdout);
    const apex_nodes::TrainResult r = apex_nodes::trainModel(samples, o.train, features);
    std::printf("trained %s on %d samples of %zu classes\n", r.kind.c_str(), r.train_samples, r.classes.size());
    if (r.validation_samples) {
      std::printf(
          "validation accuracy: %.4f (%d samples)\nconfusion matrix (a row per true label, a column per predicted one):\n%s",
          r.validation_accuracy, r.validation_samples, r.confusionTable().c_str());
    } else {
      std::printf("no samples held out: no validation accuracy\n");
    }
    r.save(o.model);
    std::printf("model written to %s\n", o.model.c_str());
  } catch (const std::exception& e) {
    std::cerr << "apex_train: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
