// Number signs (the paper's §4.1): SampleExport's crops and index, the digit MLP (features,
// training, the model file), DigitClassifier's model handling, DigitScore and DrawRegions'
// labels. Signs are drawn here with OpenCV's fonts, as apex_make_demo_bag draws them.
#include <gmock/gmock.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "apex_nodes/digits.hpp"
#include "apex_nodes/types.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using apex_nodes::DigitModel;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

struct Style {
  int font;
  double scale;  // of the sign's height
  int thickness;
  double shear;
};

/** A dark sign with a light digit, `size` pixels, as a gray crop. */
cv::Mat sign(int digit, const Style& s, cv::Size size = {80, 90}) {
  cv::Mat glyph(size, CV_8U, cv::Scalar(0));
  const std::string text = std::to_string(digit);
  const double scale = cv::getFontScaleFromHeight(s.font, cvRound(size.height * s.scale), s.thickness);
  int base = 0;
  const cv::Size t = cv::getTextSize(text, s.font, scale, s.thickness, &base);
  cv::putText(glyph, text, {(size.width - t.width) / 2, (size.height + t.height) / 2}, s.font, scale, 255, s.thickness,
              cv::LINE_AA);
  const cv::Mat shear = (cv::Mat_<double>(2, 3) << 1, s.shear, -s.shear * size.height / 2, 0, 1, 0);
  cv::warpAffine(glyph, glyph, shear, size);
  cv::Mat out(size, CV_8U, cv::Scalar(30));
  out.setTo(cv::Scalar(235), glyph > 128);
  return out;
}

std::vector<Style> styles(const std::vector<double>& scales, const std::vector<double>& shears) {
  std::vector<Style> out;
  for (int font : {cv::FONT_HERSHEY_SIMPLEX, cv::FONT_HERSHEY_DUPLEX, cv::FONT_HERSHEY_COMPLEX, cv::FONT_HERSHEY_TRIPLEX})
    for (double scale : scales)
      for (int thickness : {2, 4})
        for (double shear : shears) out.push_back({font, scale, thickness, shear});
  return out;
}

/** Every digit in every style, with its label. */
void samples(const std::vector<Style>& all, std::vector<cv::Mat>& x, std::vector<int>& y) {
  for (int d = 0; d < 10; ++d)
    for (const auto& s : all) {
      x.push_back(sign(d, s));
      y.push_back(d);
    }
}

std::string tempPath(const std::string& name) {
  static int n = 0;
  return ::testing::TempDir() + "/apex_digits_" + std::to_string(::getpid()) + "_" + std::to_string(++n) + "_" + name;
}

/** One model for the tests, trained once on 4 fonts x 2 sizes x 2 strokes x 3 slants per digit. */
const DigitModel& trainedModel() {
  static const DigitModel* model = [] {
    std::vector<cv::Mat> x;
    std::vector<int> y;
    samples(styles({0.55, 0.75}, {-0.2, 0.0, 0.2}), x, y);
    apex_nodes::TrainSettings settings;
    settings.epochs = 150;
    return new DigitModel(DigitModel::train(x, y, {}, settings));
  }();
  return *model;
}

std::shared_ptr<apex_nodes::Image> image(const cv::Mat& mat, std::uint64_t stamp = 1000000000) {
  auto img = std::make_shared<apex_nodes::Image>();
  img->header.stamp.fromNSec(stamp);
  img->encoding = mat.channels() == 1 ? "mono8" : "bgr8";
  img->mat = mat;
  return img;
}

std::shared_ptr<apex_nodes::Regions> regions(const cv::Size& size, const std::vector<cv::Rect>& boxes,
                                             const std::vector<int>& labels = {}, std::uint64_t stamp = 1000000000) {
  auto r = std::make_shared<apex_nodes::Regions>();
  r->header.stamp.fromNSec(stamp);
  r->image_size = size;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    apex_nodes::Region region;
    region.box = boxes[i];
    if (i < labels.size()) region.label = labels[i], region.confidence = 0.9;
    r->regions.push_back(region);
  }
  return r;
}

/** A 320x240 frame with signs 3 and 7 at known boxes, and its truth file (stamp 1 s). */
struct Frame {
  cv::Mat mat{240, 320, CV_8U, cv::Scalar(190)};
  std::vector<cv::Rect> boxes{{20, 30, 80, 90}, {200, 100, 80, 90}};
  std::string truth = tempPath("truth.yaml");
  Frame() {
    const Style s{cv::FONT_HERSHEY_SIMPLEX, 0.7, 3, 0.0};
    sign(3, s).copyTo(mat(boxes[0]));
    sign(7, s).copyTo(mat(boxes[1]));
    std::ofstream(truth)
        << "frames:\n  - {stamp: 1000000000, signs: 2, boxes: [[20, 30, 80, 90], [200, 100, 80, 90]], digits: [3, 7]}\n";
  }
};

std::vector<Message> feed(NodeHarness& h, const std::shared_ptr<const apex_nodes::Image>& img,
                          const std::shared_ptr<const apex_nodes::Regions>& r) {
  return {Message::share<apex_nodes::Image>(img), Message::share<apex_nodes::Regions>(r)};
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// ---------------------------------------------------------------- SampleExport

TEST(SampleExport, WritesTheCropOfEachMatchedRegionUnderItsDigitWithAnIndex) {
  Frame f;
  const std::string dir = tempPath("samples");  // made by the node
  NodeHarness h("apex_nodes/SampleExport", {"image", "regions"}, "written");
  h.set("truth", f.truth);
  h.set("directory", dir);
  // both signs, a little off; and a region on no sign, which is not exported
  const auto found = regions(f.mat.size(), {{22, 31, 78, 88}, {200, 100, 80, 90}, {150, 5, 30, 20}});
  Message m = h.run(feed(h, image(f.mat), found));
  ASSERT_FALSE(m.isNothing()) << h.error();
  EXPECT_EQ(*m.as<int>(), 2);
  const cv::Mat three = cv::imread(dir + "/3/1000000000_0.png", cv::IMREAD_UNCHANGED);
  const cv::Mat seven = cv::imread(dir + "/7/1000000000_1.png", cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(three.empty());
  ASSERT_FALSE(seven.empty());
  EXPECT_EQ(cv::norm(three, f.mat(cv::Rect(22, 31, 78, 88)), cv::NORM_INF), 0);  // the region's pixels exactly
  EXPECT_EQ(cv::norm(seven, f.mat(f.boxes[1]), cv::NORM_INF), 0);
  EXPECT_EQ(read(dir + "/index.csv"),
            "file,label,stamp_ns,x,y,width,height\n"
            "3/1000000000_0.png,3,1000000000,22,31,78,88\n"
            "7/1000000000_1.png,7,1000000000,200,100,80,90\n");
  // The same frame again (a second pass) rewrites the same samples: the index does not grow.
  m = h.run(feed(h, image(f.mat), found));
  EXPECT_EQ(*m.as<int>(), 2);
  const std::string index = read(dir + "/index.csv");
  EXPECT_EQ(std::count(index.begin(), index.end(), '\n'), 3);
  // At the end of the sequence: the index's size.
  NodeHarness total("apex_nodes/SampleExport", {"image", "regions"}, "samples");
  total.set("truth", f.truth);
  total.set("directory", dir);
  total.run(feed(total, image(f.mat), found));
  m = total.run({Message::endOfSequence(), Message::endOfSequence()});
  ASSERT_FALSE(m.isNothing()) << total.error();
  EXPECT_EQ(*m.as<int>(), 2);  // the index it found in the folder, and this frame's (the same) samples
}

TEST(SampleExport, WithNegativesARegionOnNoSignIsWrittenUnderThatLabel) {
  Frame f;
  const std::string dir = tempPath("negatives");
  NodeHarness h("apex_nodes/SampleExport", {"image", "regions"}, "written");
  h.set("truth", f.truth);
  h.set("directory", dir);
  h.set("negatives", "10");
  // a sign; a region on no sign (a hard negative); one over part of a sign (neither: not written)
  const auto found = regions(f.mat.size(), {{22, 31, 78, 88}, {150, 5, 30, 20}, {250, 150, 60, 60}});
  const Message m = h.run(feed(h, image(f.mat), found));
  ASSERT_FALSE(m.isNothing()) << h.error();
  EXPECT_EQ(*m.as<int>(), 2);
  const cv::Mat negative = cv::imread(dir + "/10/1000000000_1.png", cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(negative.empty());
  EXPECT_EQ(cv::norm(negative, f.mat(cv::Rect(150, 5, 30, 20)), cv::NORM_INF), 0);
  EXPECT_EQ(read(dir + "/index.csv"),
            "file,label,stamp_ns,x,y,width,height\n"
            "10/1000000000_1.png,10,1000000000,150,5,30,20\n"
            "3/1000000000_0.png,3,1000000000,22,31,78,88\n");
}

TEST(SampleExport, AFileAtASamplesNameThatTheIndexDoesNotListIsLeftAsItIsUnlessOverwrite) {
  Frame f;
  const std::string dir = tempPath("not_samples");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir + "/3");
  std::ofstream(dir + "/3/1000000000_0.png") << "the user's file";  // no index.csv: not a sample
  NodeHarness h("apex_nodes/SampleExport", {"image", "regions"}, "written");
  h.set("truth", f.truth);
  h.set("directory", dir);
  EXPECT_TRUE(h.run(feed(h, image(f.mat), regions(f.mat.size(), f.boxes))).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("'" + dir +
                                   "/3/1000000000_0.png' exists and is not a sample of index.csv: left as "
                                   "it is; set 'overwrite' to replace it, or choose another directory"));
  EXPECT_EQ(read(dir + "/3/1000000000_0.png"), "the user's file");
  h.set("overwrite", "true");
  Message m = h.run(feed(h, image(f.mat), regions(f.mat.size(), f.boxes)));
  ASSERT_FALSE(m.isNothing()) << h.error();
  EXPECT_EQ(*m.as<int>(), 2);
  EXPECT_FALSE(cv::imread(dir + "/3/1000000000_0.png").empty());
}

TEST(SampleExport, ATruthWithoutDigitsOrNoDirectoryIsAnErrorNamingIt) {
  Frame f;
  NodeHarness h("apex_nodes/SampleExport", {"image", "regions"}, "written");
  h.set("truth", f.truth);
  EXPECT_TRUE(h.run(feed(h, image(f.mat), regions(f.mat.size(), f.boxes))).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("no directory"));
  const std::string old = tempPath("old_truth.yaml");
  std::ofstream(old) << "frames:\n  - {stamp: 1000000000, signs: 2, boxes: [[20, 30, 80, 90], [200, 100, 80, 90]]}\n";
  h.set("truth", old);
  h.set("directory", tempPath("samples"));
  EXPECT_TRUE(h.run(feed(h, image(f.mat), regions(f.mat.size(), f.boxes))).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("lists no digits"));
}

// ---------------------------------------------------------------- the MLP

TEST(DigitModel, TrainedOnFewStylesItReadsUnseenSizesAndSlantsAbove85Percent) {
  const DigitModel& model = trainedModel();
  std::vector<cv::Mat> x;
  std::vector<int> y;
  samples(styles({0.65}, {-0.1, 0.1}), x, y);  // a size and slants it never saw
  EXPECT_GE(model.accuracy(x, y), 0.85);  // chance: 0.1
  EXPECT_GE(model.validationAccuracy(), 0.85);
  // A crop in colour, and one with scene around the sign, read the same.
  cv::Mat colour, framed(110, 100, CV_8U, cv::Scalar(200));
  const cv::Mat crop = sign(4, {cv::FONT_HERSHEY_DUPLEX, 0.65, 3, 0.1});
  cv::cvtColor(crop, colour, cv::COLOR_GRAY2BGR);
  crop.copyTo(framed(cv::Rect(10, 10, 80, 90)));
  EXPECT_EQ(model.classify(colour).label, 4);
  EXPECT_EQ(model.classify(framed).label, 4);
  EXPECT_GT(model.classify(crop).confidence, 0.5);
}

TEST(DigitModel, ReportsProgressPerBatchAndRoundTripsThroughItsFile) {
  std::vector<cv::Mat> x;
  std::vector<int> y;
  samples(styles({0.7}, {0.0}), x, y);
  apex_nodes::TrainSettings settings;
  settings.epochs = 30, settings.batch = 10, settings.hidden = {16};
  std::vector<int> reported;
  const DigitModel model =
      DigitModel::train(x, y, {}, settings, [&](const apex_nodes::TrainProgress& p) { reported.push_back(p.epochs); });
  EXPECT_EQ(reported, (std::vector<int>{10, 20, 30}));
  const std::string path = tempPath("model.yaml");
  model.save(path);
  const DigitModel loaded = DigitModel::load(path);
  EXPECT_EQ(loaded.classes(), model.classes());
  EXPECT_EQ(loaded.accuracy(x, y), model.accuracy(x, y));
  EXPECT_THROW(DigitModel::train({x.begin(), x.begin() + 8}, std::vector<int>(8, 1), {}, settings),
               std::invalid_argument);  // one class
}

// ---------------------------------------------------------------- DigitClassifier

TEST(DigitClassifier, LabelsEachRegionAndDrawRegionsShowsTheLabels) {
  Frame f;
  const std::string path = tempPath("model.yaml");
  trainedModel().save(path);
  NodeHarness h("apex_nodes/DigitClassifier", {"image", "regions"}, "regions");
  h.set("model", path);
  const Message m = h.run(feed(h, image(f.mat), regions(f.mat.size(), f.boxes)));
  ASSERT_FALSE(m.isNothing()) << h.error();
  const auto& out = *m.as<apex_nodes::Regions>();
  ASSERT_EQ(out.regions.size(), 2u);
  EXPECT_EQ(out.regions[0].label, 3);
  EXPECT_EQ(out.regions[1].label, 7);
  EXPECT_GT(out.regions[0].confidence, 0.5);

  NodeHarness draw("apex_nodes/DrawRegions", {"image", "regions"}, "image");
  auto unlabelled = std::make_shared<apex_nodes::Regions>(out);
  for (auto& r : unlabelled->regions) r.label = -1, r.confidence = 0;
  const cv::Mat plain = draw.run(feed(draw, image(f.mat), unlabelled)).as<apex_nodes::Image>()->mat;
  const cv::Mat labelled = draw.run(feed(draw, image(f.mat), m.as<apex_nodes::Regions>())).as<apex_nodes::Image>()->mat;
  cv::Mat differs;
  cv::compare(plain, labelled, differs, cv::CMP_NE);
  cv::extractChannel(differs, differs, 0);
  EXPECT_GT(cv::countNonZero(differs), 100);  // the labels, above the boxes
}

TEST(DigitClassifier, ARegionOfTheRejectLabelIsDropped) {
  // A model with an eleventh class, 10: what is no sign (light walls, dark plates without a digit).
  std::vector<cv::Mat> x;
  std::vector<int> y;
  samples(styles({0.7}, {0.0}), x, y);
  cv::RNG rng(3);
  for (int i = 0; i < 40; ++i) {
    cv::Mat wall(90, 80, CV_8U, cv::Scalar(i % 2 ? rng.uniform(150, 220) : rng.uniform(20, 45)));
    cv::Mat noise(wall.size(), CV_8U);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 12);
    x.push_back(wall + noise);
    y.push_back(10);
  }
  apex_nodes::TrainSettings settings;
  settings.epochs = 150;
  const std::string path = tempPath("model_with_negatives.yaml");
  DigitModel::train(x, y, {}, settings).save(path);

  Frame f;
  NodeHarness h("apex_nodes/DigitClassifier", {"image", "regions"}, "regions");
  h.set("model", path);
  const auto found = regions(f.mat.size(), {f.boxes[0], {110, 140, 80, 90}, f.boxes[1]});  // the middle one: the wall
  Message m = h.run(feed(h, image(f.mat), found));
  ASSERT_FALSE(m.isNothing()) << h.error();
  ASSERT_EQ(m.as<apex_nodes::Regions>()->regions.size(), 3u) << "without reject_label, every region goes on";
  EXPECT_EQ(m.as<apex_nodes::Regions>()->regions[1].label, 10);
  h.set("reject_label", "10");
  m = h.run(feed(h, image(f.mat), found));
  const auto& kept = m.as<apex_nodes::Regions>()->regions;
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].box, f.boxes[0]);
  EXPECT_EQ(kept[0].label, 3);
  EXPECT_EQ(kept[1].box, f.boxes[1]);
  EXPECT_EQ(kept[1].label, 7);
}

TEST(DigitClassifier, AMissingOrDamagedModelIsAnErrorAndTheRegionsGoOnUnlabelled) {
  Frame f;
  const std::string path = tempPath("model.yaml");
  trainedModel().save(path);
  NodeHarness h("apex_nodes/DigitClassifier", {"image", "regions"}, "regions");
  h.set("model", path);
  ASSERT_EQ(h.run(feed(h, image(f.mat), regions(f.mat.size(), f.boxes))).as<apex_nodes::Regions>()->regions[0].label, 3);
  const auto unlabelled = [&] {
    const Message m = h.run(feed(h, image(f.mat), regions(f.mat.size(), f.boxes)));
    return !m.isNothing() && m.as<apex_nodes::Regions>()->regions.size() == 2 &&
           m.as<apex_nodes::Regions>()->regions[0].label == -1 && m.as<apex_nodes::Regions>()->regions[0].confidence == 0;
  };
  // gone
  fs::remove(path);
  EXPECT_TRUE(unlabelled());
  EXPECT_THAT(h.error(), HasSubstr("the model '" + path + "' cannot be read: no such file"));
  // damaged: cut off half-way, then not YAML at all, then another YAML file
  const std::string text = [&] {
    const std::string other = tempPath("whole.yaml");
    trainedModel().save(other);
    return read(other);
  }();
  // (cut at a line's end, a file still parses: only its missing weights or scales show the damage)
  for (const std::string& bad : {text.substr(0, text.find("   weights:")), text.substr(0, text.rfind('\n', text.size() / 2) + 1),
                                 text.substr(0, text.size() / 2), std::string("\x01\x02 not a model {{{")}) {
    std::ofstream(path) << bad;
    EXPECT_TRUE(unlabelled());
    EXPECT_THAT(h.error(), HasSubstr("the model '" + path + "' is damaged"));
  }
  std::ofstream(path) << "%YAML:1.0\n---\nsomething_else: 1\n";
  EXPECT_TRUE(unlabelled());
  EXPECT_THAT(h.error(), HasSubstr("the model '" + path + "' is not an APEX digit model"));
  // A good file again: read at once (it changed), labels back, the error gone.
  trainedModel().save(path);
  const Message m = h.run(feed(h, image(f.mat), regions(f.mat.size(), f.boxes)));
  EXPECT_EQ(m.as<apex_nodes::Regions>()->regions[1].label, 7);
  EXPECT_EQ(h.error(), "");
}

// ---------------------------------------------------------------- DigitScore

TEST(DigitScore, SendsAccuracyAndTheConfusionMatrixAtTheEndOfTheSequence) {
  Frame f;
  NodeHarness acc("apex_nodes/DigitScore", {"regions"}, "accuracy");
  NodeHarness table("apex_nodes/DigitScore", {"regions"}, "confusion");
  for (NodeHarness* h : {&acc, &table}) {
    h->set("truth", f.truth);
    // frame 1: both right; frame 2: the 7 read as 1, plus a region on no sign; frame 3: the 3 rejected
    EXPECT_TRUE(h->run({Message::share<apex_nodes::Regions>(regions(f.mat.size(), f.boxes, {3, 7}))}).isNothing());
    h->run({Message::share<apex_nodes::Regions>(regions(f.mat.size(), {f.boxes[0], f.boxes[1], {0, 0, 5, 5}}, {3, 1, 2}))});
    h->run({Message::share<apex_nodes::Regions>(regions(f.mat.size(), {f.boxes[0]}, {-1}))});
    EXPECT_EQ(h->error(), "");
  }
  const Message a = acc.run({Message::endOfSequence()});
  ASSERT_FALSE(a.isNothing());
  EXPECT_DOUBLE_EQ(*a.as<double>(), 3.0 / 5);
  const std::string matrix = *table.run({Message::endOfSequence()}).as<std::string>();
  EXPECT_THAT(matrix, HasSubstr("         3    0    0    0    2    0    0    0    0    0    0    1"));  // two right, one '?'
  EXPECT_THAT(matrix, HasSubstr("         7    0    1    0    0    0    0    0    1    0    0    0"));  // one right, one as 1
  // The next sequence starts from zero.
  acc.run({Message::share<apex_nodes::Regions>(regions(f.mat.size(), f.boxes, {3, 7}))});
  EXPECT_DOUBLE_EQ(*acc.run({Message::endOfSequence()}).as<double>(), 1.0);
}

}  // namespace
