// apex_make_demo_bag's backgrounds, the tool run as the demos run it: with --backgrounds real the
// same seed gives the same bytes; the frames keep the synthetic frames' signs pixel for pixel
// (same boxes, same digits) and show a crop of one of the listed opencv-doc photographs
// everywhere else; a missing photograph is named and leaves neither a bag nor a truth file.
#include <cv_bridge/cv_bridge.h>
#include <gmock/gmock.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Image.h>
#include <sys/wait.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "demo_backgrounds.hpp"

namespace fs = std::filesystem;
using testing::HasSubstr;

namespace {

const cv::Size kScene(640, 480);  // the generator's upright scene

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/** The bag's camera frames, turned back upright (the camera lies on its side). */
std::vector<cv::Mat> scenes(const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  std::vector<cv::Mat> out;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/camera/image_raw"))) {
    cv::Mat upright;
    cv::rotate(cv_bridge::toCvCopy(m.instantiate<sensor_msgs::Image>(), "bgr8")->image, upright, cv::ROTATE_90_COUNTERCLOCKWISE);
    out.push_back(upright);
  }
  return out;
}

std::vector<cv::Rect> boxesOf(const YAML::Node& frame) {
  std::vector<cv::Rect> boxes;
  for (const auto& b : frame["boxes"]) boxes.emplace_back(b[0].as<int>(), b[1].as<int>(), b[2].as<int>(), b[3].as<int>());
  return boxes;
}

struct Outcome {
  int status;
  std::string errors;  // what it wrote to stderr
};

/** A folder of the test's own; NAME.bag and NAME_truth.yaml in it are a run's output. */
class MakeDemoBag : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("apex_make_demo_bag_" + std::to_string(getpid()) + "_" +
                                        testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string bag(const std::string& name) const { return path(name + ".bag"); }
  std::string truth(const std::string& name) const { return path(name + "_truth.yaml"); }
  /** apex_make_demo_bag NAME.bag NAME_truth.yaml `args`, with the environment `env` (VAR=value ...). */
  Outcome make(const std::string& name, const std::string& args, const std::string& env = "") const {
    const std::string errors = path(name + ".err");
    const std::string command =
        env + " '" APEX_MAKE_DEMO_BAG "' '" + bag(name) + "' '" + truth(name) + "' " + args + " >/dev/null 2>'" + errors + "'";
    const int rc = std::system(command.c_str());
    return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, readFile(errors)};
  }

 private:
  fs::path dir_;
};

TEST_F(MakeDemoBag, RealBackgroundsGiveTheSameBytesForTheSameSeed) {
  for (const std::string name : {"first", "second"}) {
    const Outcome r = make(name, "--seed 7 --frames 4 --backgrounds real");
    ASSERT_EQ(r.status, 0) << r.errors;
  }
  EXPECT_TRUE(readFile(bag("first")) == readFile(bag("second"))) << "the two bags differ";
  // (the truth's first line names its bag)
  const std::string a = readFile(truth("first")), b = readFile(truth("second"));
  EXPECT_EQ(a.substr(a.find('\n')), b.substr(b.find('\n')));
}

TEST_F(MakeDemoBag, RealBackgroundsKeepTheSyntheticFramesSignsAndReplaceTheRest) {
  ASSERT_EQ(make("synthetic", "--seed 7 --frames 4").status, 0);
  const Outcome r = make("real", "--seed 7 --frames 4 --backgrounds real");
  ASSERT_EQ(r.status, 0) << r.errors;
  const YAML::Node synthetic = YAML::LoadFile(truth("synthetic")), real = YAML::LoadFile(truth("real"));
  EXPECT_EQ(real["backgrounds"].as<std::string>(), "real");
  EXPECT_FALSE(synthetic["backgrounds"]);
  const auto a = scenes(bag("synthetic")), b = scenes(bag("real"));
  ASSERT_EQ(a.size(), 4u);
  ASSERT_EQ(b.size(), 4u);
  for (std::size_t f = 0; f < a.size(); ++f) {
    const auto boxes = boxesOf(synthetic["frames"][f]);
    EXPECT_EQ(boxesOf(real["frames"][f]), boxes) << "frame " << f;
    EXPECT_EQ(real["frames"][f]["digits"].as<std::vector<int>>(), synthetic["frames"][f]["digits"].as<std::vector<int>>());
    cv::Mat background(kScene, CV_8U, cv::Scalar(255));
    for (const auto& box : boxes) {
      EXPECT_EQ(cv::norm(a[f](box), b[f](box), cv::NORM_INF), 0) << "frame " << f << ": the sign at " << box << " differs";
      background(box).setTo(0);
    }
    cv::Mat differs;  // a pixel differs in any channel
    cv::compare(a[f], b[f], differs, cv::CMP_NE);
    std::vector<cv::Mat> channels;
    cv::split(differs, channels);
    differs = channels[0] | channels[1] | channels[2];
    EXPECT_GT(cv::countNonZero(differs & background), cv::countNonZero(background) * 9 / 10) << "frame " << f;
  }
}

TEST_F(MakeDemoBag, ARealBackgroundIsACropOfAListedPhotograph) {
  const Outcome r = make("real", "--seed 3 --frames 4 --backgrounds real");
  ASSERT_EQ(r.status, 0) << r.errors;
  const auto photos = apex_tools::loadBackgroundPhotos(apex_tools::opencvDataDir(), kScene);
  const YAML::Node frames = YAML::LoadFile(truth("real"))["frames"];
  const auto seen = scenes(bag("real"));
  ASSERT_EQ(seen.size(), 4u);
  for (std::size_t f = 0; f < seen.size(); ++f) {
    const YAML::Node where = frames[f]["background"];
    ASSERT_TRUE(where) << "frame " << f << " does not say where its background was cut";
    const std::string name = where["photo"].as<std::string>();
    auto photo = std::find_if(photos.begin(), photos.end(), [&](const auto& p) { return p.name == name; });
    ASSERT_NE(photo, photos.end()) << name << " is not one of the listed photographs";
    const cv::Rect crop(where["x"].as<int>(), where["y"].as<int>(), kScene.width, kScene.height);
    ASSERT_EQ(crop & cv::Rect(cv::Point(), photo->image.size()), crop) << name;
    cv::Mat background(kScene, CV_8U, cv::Scalar(255));
    for (const auto& box : boxesOf(frames[f])) background(box).setTo(0);
    EXPECT_EQ(cv::norm(seen[f], photo->image(crop), cv::NORM_INF, background), 0)
        << "frame " << f << " outside its signs is not " << name << " at " << crop;
  }
}

TEST_F(MakeDemoBag, AMissingPhotographIsNamedAndLeavesNoFiles) {
  // every listed photograph but the third, from opencv-doc's folder
  const std::string data = path("data"), missing = apex_tools::backgroundPhotoNames()[2];
  fs::create_directories(data);
  for (const auto& name : apex_tools::backgroundPhotoNames())
    if (name != missing) fs::create_symlink(apex_tools::opencvDataDir() + "/" + name, data + "/" + name);
  const Outcome r = make("real", "--frames 4 --backgrounds real", "APEX_OPENCV_DATA='" + data + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.errors, HasSubstr("'" + data + "/" + missing + "'"));
  EXPECT_THAT(r.errors, HasSubstr("opencv-doc provides it"));
  EXPECT_FALSE(fs::exists(bag("real")));
  EXPECT_FALSE(fs::exists(truth("real")));
}

TEST_F(MakeDemoBag, AnUnknownKindOfBackgroundIsRefused) {
  const Outcome r = make("odd", "--backgrounds photos");
  EXPECT_EQ(r.status, 2);
  EXPECT_THAT(r.errors, HasSubstr("--backgrounds is synthetic or real, not 'photos'"));
  EXPECT_FALSE(fs::exists(bag("odd")));
}

TEST_F(MakeDemoBag, SyntheticIsTheDefault) {
  ASSERT_EQ(make("default", "--seed 5 --frames 3").status, 0);
  ASSERT_EQ(make("synthetic", "--seed 5 --frames 3 --backgrounds=synthetic").status, 0);
  EXPECT_TRUE(readFile(bag("default")) == readFile(bag("synthetic"))) << "the two bags differ";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
