// The number-sign classifier's cost per region (the paper's §4.1): DigitClassifier's work on one
// sign, its features and its network apart, against the detection of the frame the sign is in (the
// Fig. 2 chain's threshold, closing and connected components on 640x480, the same OpenCV calls):
// interleaved and repeated. The model is trained here on signs drawn as apex_make_demo_bag draws
// them (Hershey fonts); the cost does not depend on what it learned.
//   apex_bench_digits [--quick]
#include <chrono>
#include <cstdio>
#include <cstring>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "apex_nodes/digits.hpp"
#include "spread.hpp"

using Clock = std::chrono::steady_clock;
using apex_bench::Spread;

namespace {

cv::Mat sign(int digit, int font, cv::Size size = {80, 90}) {
  cv::Mat m(size, CV_8U, cv::Scalar(30));
  const double scale = cv::getFontScaleFromHeight(font, size.height * 2 / 3, 3);
  int base = 0;
  const cv::Size t = cv::getTextSize(std::to_string(digit), font, scale, 3, &base);
  cv::putText(m, std::to_string(digit), {(size.width - t.width) / 2, (size.height + t.height) / 2}, font, scale, 235, 3,
              cv::LINE_AA);
  return m;
}

/** A frame like the demo's (gray), with four signs. */
cv::Mat frame() {
  cv::Mat m(480, 640, CV_8U);
  cv::RNG rng(7);
  rng.fill(m, cv::RNG::UNIFORM, 150, 220);
  for (int k = 0; k < 4; ++k) sign(k, cv::FONT_HERSHEY_SIMPLEX).copyTo(m(cv::Rect(40 + 150 * k, 100 + 60 * k, 80, 90)));
  return m;
}

template <class F>
double microseconds(int n, F&& f) {
  const auto t0 = Clock::now();
  for (int i = 0; i < n; ++i) f(i);
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / n;
}

volatile double sink;  // keeps results alive

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const int repeats = quick ? 3 : 9, n = quick ? 200 : 1000;
  cv::setNumThreads(1);  // one thread group's view: one core

  std::vector<cv::Mat> crops;
  std::vector<int> labels;
  for (int d = 0; d < 10; ++d)
    for (int font : {cv::FONT_HERSHEY_SIMPLEX, cv::FONT_HERSHEY_DUPLEX, cv::FONT_HERSHEY_COMPLEX, cv::FONT_HERSHEY_TRIPLEX})
      for (int w : {70, 80, 95}) crops.push_back(sign(d, font, {w, 90})), labels.push_back(d);
  apex_nodes::TrainSettings settings;
  settings.epochs = 50, settings.augment = 0;
  const auto model = apex_nodes::DigitModel::train(crops, labels, {}, settings);

  const cv::Mat gray = frame();
  const cv::Mat one = gray(cv::Rect(190, 160, 80, 90));  // a sign, as the node sees it: a view into the frame
  const cv::Mat features = apex_nodes::digitFeatures(one, model.features());
  cv::Mat binary, closed, labels_img, stats, centroids;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, {7, 7});
  Spread detect, classify, feature, network;
  for (int r = 0; r < repeats; ++r) {
    detect.add(microseconds(n / 10, [&](int) {
      cv::adaptiveThreshold(gray, binary, 255, cv::ADAPTIVE_THRESH_GAUSSIAN_C, cv::THRESH_BINARY_INV, 101, 25);
      cv::morphologyEx(binary, closed, cv::MORPH_CLOSE, kernel);
      sink = cv::connectedComponentsWithStats(closed, labels_img, stats, centroids, 8, CV_32S);
    }));
    classify.add(microseconds(n, [&](int) { sink = model.classify(one).confidence; }));
    feature.add(microseconds(n, [&](int) { sink = apex_nodes::digitFeatures(one, model.features()).at<float>(0); }));
    network.add(microseconds(n, [&](int) { sink = model.predict(features).confidence; }));
  }
  std::printf("## Reading a sign's digit (DigitClassifier)\n\n");
  std::printf(
      "One 80 x 90 sign of a 640 x 480 gray frame, the model of `apex_train_mlp` (16 x 16 features, 64\n"
      "hidden neurons, 10 classes); one thread (cv::setNumThreads(1)); %d runs interleaved; median\n"
      "(min–max), microseconds. Baseline: detecting the signs of the frame (the Fig. 2 chain's adaptive\n"
      "threshold, closing and connected components, the same OpenCV calls).\n\n",
      repeats);
  std::printf("| | per call | vs. detecting the frame |\n|---|---|---|\n");
  std::printf("| detect the frame's signs (baseline) | %s µs | 1 |\n", detect.text("%.0f").c_str());
  std::printf("| **classify one sign** (features + network) | **%s µs** | %.3f |\n", classify.text("%.1f").c_str(),
              classify.median() / detect.median());
  std::printf("| its features (binarise, cut to the digit, 16 x 16) | %s µs | %.3f |\n", feature.text("%.1f").c_str(),
              feature.median() / detect.median());
  std::printf("| its network (ANN_MLP predict) | %s µs | %.3f |\n", network.text("%.1f").c_str(),
              network.median() / detect.median());
  std::printf("\nThe demo's frames carry 2.5 signs on average: reading them costs %.0f%% of finding them.\n",
              100 * 2.5 * classify.median() / detect.median());
  return 0;
}
