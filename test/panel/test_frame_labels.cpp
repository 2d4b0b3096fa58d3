// The boxes drawn in the panel's labelling view, saved as a COCO file (frame_labels.hpp): read back
// by the node library's truth reader (loadTruth, what RegionScore reads) as the same frames, boxes
// and digits, and scored by RegionScore itself; bad input refused naming what was wrong.
#include <gmock/gmock.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "apex_nodes/truth.hpp"
#include "apex_nodes/types.hpp"
#include "apex_rviz_plugin/frame_labels.hpp"
#include "apex_test/node_harness.hpp"

using apex_rviz_plugin::FrameLabels;
using apex_rviz_plugin::LabelBox;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t kFirst = 1700000000033333333, kSecond = 1700000000133333333, kThird = 1700000001000000000;

/** This run's folder, removed at the end. */
fs::path folder() {
  static const fs::path dir = [] {
    const fs::path d = fs::path(::testing::TempDir()) / ("apex_frame_labels_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

struct RemoveFiles : ::testing::Environment {
  void TearDown() override { fs::remove_all(folder()); }
};
const auto* const kRemoveFiles = ::testing::AddGlobalTestEnvironment(new RemoveFiles);

/** Three frames as a person labels them: two signs with their digits, a box of another class, and a
 *  frame with nothing on it. */
FrameLabels threeFrames() {
  FrameLabels l;
  EXPECT_TRUE(l.add(kFirst, 640, 480, {20, 30, 80, 90, "3"}));
  EXPECT_TRUE(l.add(kFirst, 640, 480, {200, 100, 80, 90, "7"}));
  EXPECT_TRUE(l.add(kSecond, 640, 480, {40, 60, 64, 72, "5"}));
  EXPECT_TRUE(l.mark(kThird, 640, 480));
  return l;
}

using Boxes = std::map<std::uint64_t, std::vector<std::pair<cv::Rect, int>>>;

Boxes boxesOf(const apex_nodes::Truth& t) {
  Boxes out;
  for (const auto& [stamp, signs] : t.frames) {
    auto& frame = out[stamp];  // a frame without signs too
    for (const auto& sign : signs) frame.emplace_back(sign.box, sign.digit);
  }
  return out;
}

std::string saved(const FrameLabels& l, const std::string& name) {
  const std::string path = (folder() / name).string();
  const apex::Status st = saveCoco(l, path);
  EXPECT_TRUE(st) << st.message();
  return path;
}

apex_nodes::Regions regions(std::uint64_t stamp, std::vector<cv::Rect> boxes) {
  apex_nodes::Regions r;
  r.header.stamp.fromNSec(stamp);
  r.image_size = cv::Size(640, 480);
  for (const auto& b : boxes) r.regions.push_back({b, static_cast<double>(b.area()), {}});
  return r;
}

}  // namespace

TEST(FrameLabels, ASavedFileReadsBackAsTheSameFramesBoxesAndDigits) {
  const apex_nodes::Truth t = apex_nodes::loadTruth(saved(threeFrames(), "labels.json"));
  const Boxes expected{
      {kFirst, {{{20, 30, 80, 90}, 3}, {{200, 100, 80, 90}, 7}}}, {kSecond, {{{40, 60, 64, 72}, 5}}}, {kThird, {}}};
  EXPECT_EQ(boxesOf(t), expected);
  EXPECT_TRUE(t.has_digits);
  EXPECT_TRUE(t.scene.empty());  // the boxes are in the image's pixels
}

TEST(FrameLabels, ClassesThatAreNotDigitsAreSignsWithoutOneAndNamesAreEscaped) {
  FrameLabels l;
  ASSERT_TRUE(l.add(kFirst, 640, 480, {10, 10, 20, 20, "stop \"sign\" \\ left"}));
  ASSERT_TRUE(l.add(kFirst, 640, 480, {50, 10, 20, 20, "3"}));
  const apex_nodes::Truth t = apex_nodes::loadTruth(saved(l, "names.json"));
  EXPECT_EQ(boxesOf(t), (Boxes{{kFirst, {{{10, 10, 20, 20}, -1}, {{50, 10, 20, 20}, 3}}}}));
  EXPECT_FALSE(t.has_digits);
  EXPECT_THAT(apex_rviz_plugin::cocoJson(l), HasSubstr(R"("name": "stop \"sign\" \\ left")"));
}

TEST(FrameLabels, RegionScoreScoresRegionsAgainstTheSavedFile) {
  apex_test::NodeHarness h("apex_nodes/RegionScore", {"regions"}, "f1");
  h.set("truth", saved(threeFrames(), "score.json"));
  std::vector<double> f1;
  // both signs found; one found and a false region; a false region on the frame with nothing
  for (const auto& r : {regions(kFirst, {{21, 31, 80, 90}, {199, 101, 80, 90}}),
                        regions(kSecond, {{40, 60, 64, 72}, {0, 0, 9, 9}}), regions(kThird, {{5, 5, 20, 20}})}) {
    const apex::Message m = h.run({apex::Message::make(r)});
    f1.push_back(m.isNothing() ? -1 : *m.as<double>());
  }
  EXPECT_NEAR(f1[0], 1.0, 1e-9);
  EXPECT_NEAR(f1[1], 2.0 / 3.0, 1e-9);
  EXPECT_NEAR(f1[2], 0.0, 1e-9);
}

TEST(FrameLabels, ImageNamesCarryTheStampAsRosPrintsIt) {
  EXPECT_EQ(apex_rviz_plugin::frameImageName(kFirst), "frame_1700000000.033333333.png");
  EXPECT_EQ(apex_rviz_plugin::frameImageName(kThird), "frame_1700000001.000000000.png");
}

TEST(FrameLabels, BoxesAreCutToTheImageAndEmptyOnesIgnoredSayingSo) {
  FrameLabels l;
  ASSERT_TRUE(l.add(kFirst, 640, 480, {600, 450, 100, 100, "a"}));  // dragged past the corner
  EXPECT_EQ(l.frame(kFirst)->boxes[0].width, 40);
  EXPECT_EQ(l.frame(kFirst)->boxes[0].height, 30);
  const apex::Status line = l.add(kFirst, 640, 480, {10, 10, 0, 50, "a"});
  EXPECT_THAT(line.message(), HasSubstr("a box of 0×50 pixels in the image ignored"));
  EXPECT_THAT(l.add(kFirst, 640, 480, {700, 10, 20, 20, "a"}).message(), HasSubstr("ignored"));  // outside the image
  EXPECT_THAT(l.add(kFirst, 640, 480, {10, 10, 20, 20, "  "}).message(), HasSubstr("a box needs a class"));
  EXPECT_EQ(l.boxCount(), 1u);
  EXPECT_THAT(l.add(0, 640, 480, {10, 10, 20, 20, "a"}).message(), HasSubstr("this frame has no stamp"));
  EXPECT_EQ(l.frames().size(), 1u);
}

TEST(FrameLabels, RemoveRelabelAndUnmark) {
  FrameLabels l = threeFrames();
  ASSERT_TRUE(l.relabel(kFirst, 1, "9"));
  ASSERT_TRUE(l.remove(kFirst, 0));
  EXPECT_FALSE(l.remove(kFirst, 5));
  l.unmark(kThird);
  const apex_nodes::Truth t = apex_nodes::loadTruth(saved(l, "edited.json"));
  EXPECT_EQ(boxesOf(t), (Boxes{{kFirst, {{{200, 100, 80, 90}, 9}}}, {kSecond, {{{40, 60, 64, 72}, 5}}}}));
}

TEST(FrameLabels, ASaveThatCannotBeMadeNamesThePathAndLeavesTheOldFile) {
  const FrameLabels l = threeFrames();
  EXPECT_THAT(saveCoco(FrameLabels(), (folder() / "none.json").string()).message(), HasSubstr("no frame is labelled yet"));
  EXPECT_FALSE(fs::exists(folder() / "none.json"));
  const std::string missing = (folder() / "no_such_folder" / "labels.json").string();
  EXPECT_THAT(saveCoco(l, missing).message(), HasSubstr("cannot write '" + missing + "'"));
  EXPECT_THAT(saveCoco(l, (folder() / "labels.yaml").string()).message(), HasSubstr("ends in .json"));
  const fs::path dir = folder() / "a_folder.json";
  fs::create_directories(dir);
  EXPECT_THAT(saveCoco(l, dir.string()).message(), HasSubstr("not a regular file"));
  const std::string kept = saved(l, "kept.json");  // a file that may not be written stays as it was
  ::chmod(kept.c_str(), 0444);
  EXPECT_THAT(saveCoco(FrameLabels(threeFrames()), kept).message(), HasSubstr("read-only"));
  EXPECT_EQ(boxesOf(apex_nodes::loadTruth(kept)).size(), 3u);
}
