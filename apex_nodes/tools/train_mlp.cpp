// Trains the digit classifier (DigitClassifier's model) on samples that SampleExport wrote:
//   apex_train_mlp SAMPLES_DIR MODEL.yaml [--hidden N[,N...]] [--epochs N] [--batch N]
//                  [--validation F] [--augment N] [--size N] [--seed N]
// Reads SAMPLES_DIR/index.csv, holds a share of the samples out, adds varied copies (slant, turn,
// size) of the others, trains cv::ml::ANN_MLP (RPROP)
// with a progress line per batch of epochs, prints the validation accuracy and the time per
// classification, and writes the model with its feature settings (atomically). (apex_train trains
// Classifier's models, of any cv::ml type, on FeatureExtract's features of the same samples.)
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "apex_nodes/digits.hpp"
#include "cli.hpp"
#include "samples.hpp"

namespace {

struct Options {
  std::string samples, model;
  apex_nodes::DigitFeatureSettings features;
  apex_nodes::TrainSettings train;
};

const char* kUsage =
    "usage: apex_train_mlp SAMPLES_DIR MODEL.yaml [--hidden N[,N...]] [--epochs N] [--batch N] [--validation F]"
    " [--augment N] [--size N] [--seed N]";

int whole(const std::string& what, const std::string& text, int lo, int hi) {
  return static_cast<int>(apex_tools::number(what, text, lo, hi));
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
    if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
    const std::string value = argv[++i];
    if (arg == "--hidden") {
      o.train.hidden.clear();
      std::stringstream list(value);
      for (std::string n; std::getline(list, n, ',');) o.train.hidden.push_back(whole("--hidden", n, 1, 4096));
    } else if (arg == "--epochs") {
      o.train.epochs = whole(arg, value, 1, 100000);
    } else if (arg == "--batch") {
      o.train.batch = whole(arg, value, 1, 100000);
    } else if (arg == "--augment") {
      o.train.augment = whole(arg, value, 0, 100);
    } else if (arg == "--size") {
      o.features.size = whole(arg, value, 4, 64);
    } else if (arg == "--seed") {
      o.train.seed = static_cast<unsigned>(whole(arg, value, 0, 1 << 30));
    } else if (arg == "--validation") {
      char* end = nullptr;
      const double share = std::strtod(value.c_str(), &end);
      if (value.empty() || *end || !(share >= 0 && share <= 0.9))
        throw std::invalid_argument("--validation needs a share from 0 to 0.9, not '" + value + "'");
      o.train.validation = share;
    } else {
      throw std::invalid_argument("unknown option '" + arg + "'");
    }
  }
  if (plain.size() != 2) throw std::invalid_argument("needs SAMPLES_DIR and MODEL.yaml");
  o.samples = plain[0], o.model = plain[1];
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    o = parse(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "apex_train_mlp: " << e.what() << "\n" << kUsage << "\n";
    return 2;
  }
  try {
    std::vector<cv::Mat> crops;
    std::vector<int> labels;
    apex_tools::readSamples(o.samples, cv::IMREAD_GRAYSCALE, crops, labels);
    std::printf("apex_train_mlp: %zu samples from %s, %.0f%% held out for validation, %d varied copies of the others\n",
                crops.size(), o.samples.c_str(), 100 * o.train.validation, o.train.augment);
    std::fflush(stdout);
    const auto model = apex_nodes::DigitModel::train(crops, labels, o.features, o.train, [](const auto& p) {
      std::printf("epoch %5d: training accuracy %.3f, validation accuracy %.3f\n", p.epochs, p.train_accuracy,
                  p.validation_accuracy);
      std::fflush(stdout);
    });
    const auto start = std::chrono::steady_clock::now();
    for (const auto& c : crops) (void)model.classify(c);
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() / crops.size();
    model.save(o.model);
    std::printf("validation accuracy: %.3f; %.1f us per crop (features and network); model written to %s\n",
                model.validationAccuracy(), us, o.model.c_str());
  } catch (const std::exception& e) {
    std::cerr << "apex_train_mlp: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
