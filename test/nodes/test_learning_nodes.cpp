// Learning (learning.hpp, training.hpp): FeatureExtract against the OpenCV calls made directly,
// Classifier against cv::ml models trained and run directly, apex_train's training on CSV samples,
// and Classifier's errors. Real data: opencv-doc's digits.png, 5,000 handwritten digits of 20x20
// pixels, 50 rows of 100, five rows per digit (0 first); and fruits.jpg for colour.
#include <gmock/gmock.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <opencv2/ml.hpp>
#include <opencv2/objdetect.hpp>

#include "apex_nodes/learning.hpp"
#include "apex_nodes/training.hpp"
#include "apex_test/real_images.hpp"

using namespace apex_test;
using apex_nodes::Features;
using apex_nodes::Regions;
using ::testing::HasSubstr;

namespace {

constexpr int kCell = 20, kDigits = 5000;

const cv::Mat& digitsImage() {
  static const cv::Mat image = readGrayData("digits.png");
  return image;
}
cv::Rect cellBox(int i) { return {(i % 100) * kCell, (i / 100) * kCell, kCell, kCell}; }
int digitOf(int i) { return i / 500; }
cv::Mat cell(int i) { return digitsImage()(cellBox(i)).clone(); }

/** The first (or second) half of each digit's 500 cells, in order. */
std::vector<int> half(bool first) {
  std::vector<int> out;
  for (int i = 0; i < kDigits; ++i)
    if ((i % 500 < 250) == first) out.push_back(i);
  return out;
}

std::shared_ptr<Regions> regionsAt(const cv::Mat& image, const std::vector<cv::Rect>& boxes) {
  auto r = std::make_shared<Regions>();
  r->header.stamp = ros::Time(42, 7);
  r->header.frame_id = "camera";
  r->image_size = image.size();
  for (const auto& b : boxes) {
    apex_nodes::Region region;
    region.box = b;
    region.area = b.area();
    r->regions.push_back(region);
  }
  return r;
}
std::shared_ptr<Regions> cellRegions(const std::vector<int>& cells) {
  std::vector<cv::Rect> boxes;
  for (int i : cells) boxes.push_back(cellBox(i));
  return regionsAt(digitsImage(), boxes);
}

/** FeatureExtract's features of `regions` in `image`, with `params` set; fails if it sent none. */
Message extract(const cv::Mat& image, const std::shared_ptr<const Regions>& regions,
                const std::vector<std::pair<std::string, std::string>>& params) {
  NodeHarness h("apex_nodes/FeatureExtract", {"image", "regions"}, "features");
  for (const auto& [name, value] : params) h.set(name, value);
  const Message m = h.run({Message::share<apex_nodes::Image>(imageOf(image, image.channels() == 1 ? "mono8" : "bgr8")),
                           Message::share<Regions>(regions)});
  EXPECT_TRUE(m.as<Features>()) << h.error();
  return m;
}

// The direct computations.
cv::Mat deskew(const cv::Mat& img) {  // OpenCV's samples/python/digits.py
  const cv::Moments m = cv::moments(img);
  if (std::abs(m.mu02) < 1e-2) return img.clone();
  const double skew = m.mu11 / m.mu02;
  const cv::Mat warp = (cv::Mat_<double>(2, 3) << 1, skew, -0.5 * img.rows * skew, 0, 1, 0);
  cv::Mat out;
  cv::warpAffine(img, out, warp, img.size(), cv::WARP_INVERSE_MAP | cv::INTER_LINEAR);
  return out;
}
cv::Mat hogOf(const cv::Mat& digit, int cells, int bins, bool straighten) {
  const int c = kCell / cells;
  const cv::HOGDescriptor hog({kCell, kCell}, {2 * c, 2 * c}, {c, c}, {c, c}, bins, 1, -1, cv::HOGDescriptor::L2Hys, 0.2, false,
                              64, true);
  std::vector<float> values;
  hog.compute(straighten ? deskew(digit) : digit, values, {kCell, kCell}, {0, 0});
  return cv::Mat(values, true).reshape(1, 1);
}

template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

std::string tempPath(const std::string& name) {
  static int n = 0;
  return ::testing::TempDir() + "/apex_learning_" + std::to_string(::getpid()) + "_" + std::to_string(++n) + "_" + name;
}

// ---------------------------------------------------------------- FeatureExtract

TEST(FeatureExtract, HogIsTheHogDescriptorsOfTheRegionsInTheirOrder) {
  const std::vector<int> some{4999, 0, 777, 1234, 2500, 3141};
  auto regions = cellRegions(some);
  apex_nodes::Region outside = regions->regions[0];
  outside.box = {5000, 5000, 20, 20};  // outside the image: a row of zeros
  regions->regions.push_back(outside);
  struct Case {
    int cells, bins;
    bool deskew;
    int length;
    std::string settings;
  };
  for (const Case& c : {Case{2, 16, false, 64, "hog size=20 cells=2 bins=16 deskew=0"},  // digits.py's layout
                        Case{4, 9, true, 324, "hog size=20 cells=4 bins=9 deskew=1"}}) {
    const Message m =
        extract(digitsImage(), regions,
                {{"cells", std::to_string(c.cells)}, {"bins", std::to_string(c.bins)}, {"deskew", c.deskew ? "true" : "false"}});
    const Features& f = *m.as<Features>();
    EXPECT_EQ(f.length, c.length);
    EXPECT_EQ(f.settings, c.settings);
    EXPECT_EQ(f.regions.get(), regions.get());  // the regions themselves, shared
    EXPECT_EQ(f.header.stamp, ros::Time(42, 7));
    ASSERT_EQ(f.rows.rows, 7);
    for (std::size_t k = 0; k < some.size(); ++k)
      expectSameMat(f.rows.row(static_cast<int>(k)), hogOf(cell(some[k]), c.cells, c.bins, c.deskew));
    EXPECT_EQ(f.valid, (std::vector<uchar>{1, 1, 1, 1, 1, 1, 0}));
    EXPECT_EQ(cv::countNonZero(f.rows.row(6)), 0);
  }
}

TEST(FeatureExtract, RawPixelsHuMomentsAndColourHistogramsAreTheirDirectComputations) {
  const std::vector<int> some{3, 1500, 4321};
  const auto regions = cellRegions(some);
  const Message raw = extract(digitsImage(), regions, {{"method", "raw_pixels"}, {"size", "10"}});
  const Message hu = extract(digitsImage(), regions, {{"method", "hu_moments"}});
  EXPECT_EQ(raw.as<Features>()->length, 100);
  EXPECT_EQ(hu.as<Features>()->length, 7);
  for (std::size_t k = 0; k < some.size(); ++k) {
    cv::Mat small, want;
    cv::resize(cell(some[k]), small, {10, 10}, 0, 0, cv::INTER_AREA);
    small.reshape(1, 1).convertTo(want, CV_32F, 1.0 / 255);
    expectSameMat(raw.as<Features>()->rows.row(static_cast<int>(k)), want);
    cv::Mat mask;
    cv::threshold(cell(some[k]), mask, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    double h[7];
    cv::HuMoments(cv::moments(mask, true), h);
    cv::Mat hu_want(1, 7, CV_32F);
    for (int j = 0; j < 7; ++j)
      hu_want.at<float>(j) = h[j] == 0 ? 0.f : float(-std::copysign(1.0, h[j]) * std::log10(std::abs(h[j])));
    expectSameMat(hu.as<Features>()->rows.row(static_cast<int>(k)), hu_want);
  }
  // colour: fruits.jpg in HSV and BGR, 8 bins a channel, each the share of the region's pixels
  const cv::Mat fruits = readData("fruits.jpg");
  const std::vector<cv::Rect> boxes{{10, 20, 120, 90}, {200, 150, 64, 64}, {300, 100, 33, 71}};
  for (const std::string space : {"hsv", "bgr"}) {
    const Message m =
        extract(fruits, regionsAt(fruits, boxes), {{"method", "color_histogram"}, {"bins", "8"}, {"color_space", space}});
    ASSERT_EQ(m.as<Features>()->length, 24);
    for (std::size_t k = 0; k < boxes.size(); ++k) {
      cv::Mat crop = fruits(boxes[k]).clone();
      if (space == "hsv") cv::cvtColor(crop, crop, cv::COLOR_BGR2HSV);
      cv::Mat want;
      for (int c = 0; c < 3; ++c) {
        const float range[] = {0.f, space == "hsv" && c == 0 ? 180.f : 256.f};
        const float* ranges[] = {range};
        const int bins = 8;
        cv::Mat hist;
        cv::calcHist(&crop, 1, &c, cv::Mat(), hist, 1, &bins, ranges);
        want.push_back(hist / double(boxes[k].area()));
      }
      expectSameMat(m.as<Features>()->rows.row(static_cast<int>(k)), want.reshape(1, 1));
      EXPECT_NEAR(cv::sum(want)[0], 3.0, 1e-5);
    }
  }
}

// ---------------------------------------------------------------- Classifier

TEST(Classifier, LabelsHeldOutDigitsExactlyAsTheSvmAndKNearestTrainedDirectly) {
  cv::Mat train_x, test_x;
  std::vector<int> train_y, test_y;
  for (int i : half(true)) train_x.push_back(hogOf(cell(i), 4, 9, true)), train_y.push_back(digitOf(i));
  for (int i : half(false)) test_x.push_back(hogOf(cell(i), 4, 9, true)), test_y.push_back(digitOf(i));
  auto svm = cv::ml::SVM::create();
  svm->setType(cv::ml::SVM::C_SVC);
  svm->setKernel(cv::ml::SVM::RBF);
  svm->setC(2.67);  // digits.py's C; a gamma for 324 features rather than its 64
  svm->setGamma(0.5);
  svm->train(train_x, cv::ml::ROW_SAMPLE, cv::Mat(train_y));
  auto knn = cv::ml::KNearest::create();
  knn->setDefaultK(3);
  cv::Mat responses;
  cv::Mat(train_y).convertTo(responses, CV_32F);
  knn->train(train_x, cv::ml::ROW_SAMPLE, responses);
  const std::string svm_file = tempPath("digits_svm.yaml"), knn_file = tempPath("digits_knn.yaml");
  svm->save(svm_file);
  knn->save(knn_file);
  cv::Mat svm_labels, knn_labels, neighbours;
  svm->predict(test_x, svm_labels);
  knn->findNearest(test_x, 3, knn_labels, neighbours);

  // The held-out cells through FeatureExtract (the same features as the direct ones), then Classifier.
  const std::vector<int> held_out = half(false);
  const Message features = extract(digitsImage(), cellRegions(held_out), {{"cells", "4"}, {"bins", "9"}, {"deskew", "true"}});
  expectSameMat(features.as<Features>()->rows, test_x);
  for (const auto& [file, want] : {std::pair{svm_file, svm_labels}, std::pair{knn_file, knn_labels}}) {
    NodeHarness h("apex_nodes/Classifier", {"features"}, "regions");
    h.set("model", file);
    const Message m = h.run({features});
    ASSERT_TRUE(m.as<Regions>()) << h.error();
    EXPECT_EQ(h.error(), "");
    const auto& out = m.as<Regions>()->regions;
    ASSERT_EQ(out.size(), test_y.size());
    int right = 0, same = 0;
    for (std::size_t i = 0; i < out.size(); ++i) {
      const int direct = cvRound(want.at<float>(static_cast<int>(i)));
      same += out[i].label == direct;
      right += out[i].label == test_y[i];
      EXPECT_EQ(out[i].box, cellBox(held_out[i]));
      if (file == knn_file) {  // the share of the 3 neighbours with the label
        const int agree = cv::countNonZero(neighbours.row(static_cast<int>(i)) == want.at<float>(static_cast<int>(i)));
        EXPECT_DOUBLE_EQ(out[i].confidence, agree / 3.0);
      } else {
        EXPECT_EQ(out[i].confidence, 1.0);  // ten classes: an SVM's label has no confidence
      }
    }
    EXPECT_EQ(same, static_cast<int>(out.size())) << file;
    const double accuracy = static_cast<double>(right) / out.size();
    std::printf("%s on the 2,500 held-out digits: accuracy %.4f\n", file == svm_file ? "SVM" : "KNearest (k=3)", accuracy);
    EXPECT_GT(accuracy, 0.9);
  }
  // min_confidence: a k-NN label fewer than all 3 neighbours agree on is rejected
  NodeHarness strict("apex_nodes/Classifier", {"features"}, "regions");
  strict.set("model", knn_file);
  strict.set("min_confidence", "0.9");
  const Message strict_out = strict.run({features});
  ASSERT_TRUE(strict_out.as<Regions>()) << strict.error();
  const auto& out = strict_out.as<Regions>()->regions;
  for (std::size_t i = 0; i < out.size(); ++i)
    EXPECT_EQ(out[i].label, out[i].confidence >= 0.9 ? cvRound(knn_labels.at<float>(int(i))) : -1);
}

// ---------------------------------------------------------------- apex_train

/** Three clusters, labels 2, 5 and 7 around (0, 0), (10, 0) and (0, 10): 30 points each. */
std::string toyCsv() {
  const std::string path = tempPath("toy.csv");
  std::ofstream out(path);
  out << "label,x,y\n";
  cv::RNG rng(7);
  const int labels[] = {2, 5, 7};
  const double x[] = {0, 10, 0}, y[] = {0, 0, 10};
  for (int i = 0; i < 90; ++i)
    out << labels[i % 3] << "," << x[i % 3] + rng.uniform(-1.0, 1.0) << "," << y[i % 3] + rng.uniform(-1.0, 1.0) << "\n";
  return path;
}

std::shared_ptr<Features> points(const std::vector<cv::Point2f>& at, const std::string& settings = "") {
  auto f = std::make_shared<Features>();
  f->rows = cv::Mat(at, true).reshape(1, static_cast<int>(at.size()));
  f->length = 2;
  f->valid.assign(at.size(), 1);
  f->settings = settings;
  f->regions = regionsAt(cv::Mat(100, 100, CV_8U), std::vector<cv::Rect>(at.size(), cv::Rect(0, 0, 5, 5)));
  return f;
}

TEST(ApexTrain, EachModelLearnsASeparableCsvAndClassifierReadsItsFile) {
  const apex_nodes::Samples samples = apex_nodes::readCsv(toyCsv());
  ASSERT_EQ(samples.rows.size(), cv::Size(2, 90));
  for (const std::string kind : {"svm", "rtrees", "knn", "mlp", "boost"}) {
    apex_nodes::Samples s = samples;
    if (kind == "boost") {  // two classes only: the 2s and 5s
      s = {};
      for (int i = 0; i < samples.rows.rows; ++i)
        if (samples.labels[i] != 7) s.rows.push_back(samples.rows.row(i)), s.labels.push_back(samples.labels[i]);
    }
    apex_nodes::ModelOptions o;
    o.model = kind;
    o.svm_gamma = 0.05;  // for distances of about 10
    const apex_nodes::TrainResult r = apex_nodes::trainModel(s, o);
    EXPECT_EQ(r.validation_samples, std::lround(0.2 * s.rows.rows)) << kind;
    EXPECT_EQ(r.train_samples + r.validation_samples, s.rows.rows);
    EXPECT_EQ(r.validation_accuracy, 1.0) << kind << "\n" << r.confusionTable();
    int diagonal = 0;
    for (std::size_t t = 0; t < r.confusion.size(); ++t)
      for (std::size_t p = 0; p < r.confusion[t].size(); ++p) {
        if (t == p) diagonal += r.confusion[t][p];
        else EXPECT_EQ(r.confusion[t][p], 0) << kind << ": true " << r.classes[t] << ", predicted column " << p;
      }
    EXPECT_EQ(diagonal, r.validation_samples);
    EXPECT_EQ(apex_nodes::trainModel(s, o).confusion, r.confusion);  // the same seed, the same split
    const std::string file = tempPath(kind + ".yaml");
    r.save(file);
    NodeHarness h("apex_nodes/Classifier", {"features"}, "regions");
    h.set("model", file);
    const Message m = h.run<Features>(points({{0.2f, -0.3f}, {9.5f, 0.5f}, {0.5f, 10.2f}}));
    ASSERT_TRUE(m.as<Regions>()) << h.error();
    EXPECT_EQ(h.error(), "") << kind;
    const auto& out = m.as<Regions>()->regions;
    EXPECT_EQ(out[0].label, 2) << kind;
    EXPECT_EQ(out[1].label, 5) << kind;
    if (kind != "boost") EXPECT_EQ(out[2].label, 7) << kind;
    for (const auto& region : out) EXPECT_TRUE(region.confidence > 0 && region.confidence <= 1) << kind;
  }
  apex_nodes::ModelOptions boost;
  boost.model = "boost";
  EXPECT_THAT(errorOf([&] { apex_nodes::trainModel(samples, boost); }),
              HasSubstr("boost tells two classes apart, these samples have 3"));
}

TEST(ApexTrain, AMalformedCsvLineIsAnErrorNamingItsLine) {
  const auto csv = [](const std::string& text) {
    const std::string path = tempPath("bad.csv");
    std::ofstream(path) << text;
    return path;
  };
  std::string path = csv("label,x,y\n1,0.5,0.25\n\n2,0.5,abc\n");
  EXPECT_THAT(errorOf([&] { apex_nodes::readCsv(path); }), HasSubstr(path + " line 4: feature 2 ('abc') is not a number"));
  path = csv("1,0.5,0.25\n2,0.5\n");
  EXPECT_THAT(errorOf([&] { apex_nodes::readCsv(path); }), HasSubstr(path + " line 2: has 1 features, line 1 has 2"));
  path = csv("1,0.5\n-1,0.5\n");
  EXPECT_THAT(errorOf([&] { apex_nodes::readCsv(path); }),
              HasSubstr(path + " line 2: the label '-1' is not a whole number >= 0"));
  path = csv("label,x\n");
  EXPECT_THAT(errorOf([&] { apex_nodes::readCsv(path); }), HasSubstr("lists no samples"));
  EXPECT_THAT(errorOf([&] { apex_nodes::readCsv(tempPath("none.csv")); }), HasSubstr("cannot read"));
}

// ---------------------------------------------------------------- Classifier's errors

TEST(Classifier, AMissingDamagedOrMismatchedModelIsAnErrorNamingTheFileAndTheRegionsGoOnUnlabelled) {
  NodeHarness h("apex_nodes/Classifier", {"features"}, "regions");
  const auto unlabelled = [&](const std::shared_ptr<Features>& f) {
    const Message m = h.run<Features>(f);
    return m.as<Regions>() && m.as<Regions>()->regions.size() == f->regions->regions.size() &&
           m.as<Regions>()->regions[0].label == -1;
  };
  const auto toy = points({{0.2f, -0.3f}, {9.5f, 0.5f}});
  const std::string path = tempPath("model.yaml");
  h.set("model", path);
  EXPECT_TRUE(unlabelled(toy));
  EXPECT_THAT(h.error(), HasSubstr("the model '" + path + "' cannot be read: no such file"));

  std::ofstream(path) << "\x01\x02 not a model {{{";
  EXPECT_TRUE(unlabelled(toy));
  EXPECT_THAT(h.error(), HasSubstr("the model '" + path + "' is damaged"));
  std::ofstream(path) << "%YAML:1.0\n---\nsomething_else: 1\n";
  EXPECT_TRUE(unlabelled(toy));
  EXPECT_THAT(h.error(),
              HasSubstr("the model '" + path + "' is not a model Classifier knows: its first node is 'something_else'"));

  // A model of two features (trained on the toy CSV, recorded as HOG's), given HOG's 64 features.
  apex_nodes::ModelOptions o;
  o.svm_gamma = 0.05;
  const apex_nodes::TrainResult r =
      apex_nodes::trainModel(apex_nodes::readCsv(toyCsv()), o, "hog size=20 cells=2 bins=16 deskew=0");
  r.save(path);
  const Message hog = extract(digitsImage(), cellRegions({0, 1}), {});
  EXPECT_TRUE(h.run({hog}).as<Regions>());
  EXPECT_THAT(h.error(), HasSubstr("the model '" + path + "' (svm) takes 2 features per region, but these have 64 (hog size=20"));
  // Two features, but not the ones it was trained on.
  EXPECT_TRUE(unlabelled(points({{0.2f, -0.3f}}, "x and y")));
  EXPECT_THAT(h.error(), HasSubstr("was trained on the features 'hog size=20 cells=2 bins=16 deskew=0', these are 'x and y'"));
  // The right features: labelled, the error gone.
  const Message m = h.run<Features>(points({{0.2f, -0.3f}}, "hog size=20 cells=2 bins=16 deskew=0"));
  EXPECT_EQ(m.as<Regions>()->regions[0].label, 2);
  EXPECT_EQ(h.error(), "");
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
