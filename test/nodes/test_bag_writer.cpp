// BagWriter as a recorder: what BagReader plays back is what was recorded, at the
// messages' own stamps; a file appears under its name only when complete; split
// files; start/stop; a type with no ROS message is a clear error on the node.
#include <gmock/gmock.h>
#include <rosbag/view.h>
#include <std_msgs/Int32.h>

#include <filesystem>
#include <fstream>

#include "apex_nodes/types.hpp"
#include "apex_test/node_harness.hpp"
#include "apex_test/test_bags.hpp"

using namespace apex_test;
using testing::HasSubstr;
namespace fs = std::filesystem;

/** A type with no ROS message (no inspector registered). */
struct NoRosForm {};
APEX_TYPE_NAME(NoRosForm, "test/NoRosForm");

namespace {

const char* kTopics = "[/camera/image_raw, /camera/points]";

std::string fresh(const std::string& name) {
  const fs::path dir = bagDirectory() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

void set(Graph& g, const std::string& node, const std::string& param, const std::string& value) {
  auto r = g.setParameter(node, param, value);
  ASSERT_TRUE(r) << r.message();
}

std::string errorOf(Graph& g, const std::string& node) {
  for (const auto& s : g.nodeStats())
    if (s.name == node) return s.error;
  return "no node '" + node + "'";
}

/** A BagWriter "rec" recording `topics` into `file`, fed by a test/MessageFeeder "feed" on
 *  input `input`. */
void feedRecorder(Graph& g, const std::string& topics, const std::string& file, const std::string& input) {
  add(g, "apex_nodes/BagWriter", "rec");
  set(g, "rec", "topics", topics);
  set(g, "rec", "file", file);
  add(g, "test/MessageFeeder", "feed");
  link(g, "feed", "out", "rec", input);
  g.start();
}

/** A bag's messages on `topic` in order, as `M`, with their record times. */
template <class M>
std::vector<std::pair<ros::Time, boost::shared_ptr<M>>> readTopic(const std::string& file, const std::string& topic) {
  rosbag::Bag bag(file, rosbag::bagmode::Read);
  std::vector<std::pair<ros::Time, boost::shared_ptr<M>>> out;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery(topic)))
    out.emplace_back(m.getTime(), m.instantiate<M>());
  return out;
}

/** A player of `source` (as fast as taken, one pass) into a recorder of both camera topics. */
class Recording {
 public:
  Recording(const std::string& source, const std::string& file,
            const std::vector<std::pair<std::string, std::string>>& params = {})
      : g_(pluginRegistry()) {
    add(g_, "apex_nodes/BagReader", "bag");
    set(g_, "bag", "topics", kTopics);
    set(g_, "bag", "rate", "0");
    set(g_, "bag", "file", source);
    add(g_, "apex_nodes/BagWriter", "rec");
    set(g_, "rec", "topics", kTopics);
    set(g_, "rec", "file", file);
    for (const auto& [param, value] : params) set(g_, "rec", param, value);
    link(g_, "bag", "camera_image_raw", "rec", "camera_image_raw");
    link(g_, "bag", "camera_points", "rec", "camera_points");
    g_.start();
  }
  Graph& graph() { return g_; }
  bool recording() { return std::get<bool>(g_.parameterValue("rec", "recording").value()); }

 private:
  Graph g_;
};

TEST(BagWriter, WhatBagReaderPlaysBackIsWhatWasRecordedAtTheMessagesOwnStamps) {
  const std::string out = fresh("round_trip") + "/out.bag";
  {
    Recording r(writeBag(5), out);
    // the pass's end stops the recording and closes the file: then, and only then, it has its name
    ASSERT_TRUE(waitUntil([&] { return !r.recording(); }));
    EXPECT_TRUE(fs::exists(out));
    EXPECT_FALSE(fs::exists(out + ".active"));
    EXPECT_EQ(errorOf(r.graph(), "rec"), "");
  }
  const auto images = readTopic<sensor_msgs::Image>(out, "/camera/image_raw");
  const auto clouds = readTopic<sensor_msgs::PointCloud2>(out, "/camera/points");
  ASSERT_EQ(images.size(), 5u);
  ASSERT_EQ(clouds.size(), 5u);
  for (int k = 0; k < 5; ++k) {
    SCOPED_TRACE(k);
    ASSERT_TRUE(images[k].second && clouds[k].second);
    EXPECT_EQ(images[k].first, frameTime(k));  // the record time is the message's own stamp
    EXPECT_EQ(images[k].second->header.stamp, frameTime(k));
    EXPECT_EQ(images[k].second->data, image(k).data);
    EXPECT_EQ(images[k].second->encoding, "mono8");
    EXPECT_EQ(clouds[k].first, frameTime(k));  // not the source bag's record time (5 ms later)
    EXPECT_EQ(clouds[k].second->width * clouds[k].second->height, 1u);
  }

  // Played back: five frames of an image and a cloud each, as recorded.
  Graph g(pluginRegistry());
  add(g, "apex_nodes/BagReader", "bag");
  set(g, "bag", "topics", kTopics);
  set(g, "bag", "rate", "0");
  set(g, "bag", "file", out);
  add(g, "test/Collector", "images");
  add(g, "test/Collector", "clouds");
  link(g, "bag", "camera_image_raw", "images", "in");
  link(g, "bag", "camera_points", "clouds", "in");
  g.start();
  auto& got = *object<Collector>(g, "images");
  ASSERT_TRUE(got.waitFor(5));
  ASSERT_TRUE(object<Collector>(g, "clouds")->waitFor(5));
  ASSERT_TRUE(g.waitIdle(kWait));
  ASSERT_EQ(got.size(), 5u);
  for (int k = 0; k < 5; ++k) {
    auto played = got.messages()[k].as<apex_nodes::Image>();
    ASSERT_TRUE(played);
    EXPECT_EQ(played->header.stamp, frameTime(k));
    EXPECT_EQ(played->mat.at<std::uint8_t>(1, 2), k);
  }
}

TEST(BagWriter, SplitsIntoNumberedFilesThatTogetherHoldEveryFrame) {
  const std::string dir = fresh("split");
  {
    Recording r(writeBag(6), dir + "/parts.bag", {{"split_size", "0.002"}});  // 2 kB: a bag's header alone is 4 kB
    ASSERT_TRUE(waitUntil([&] { return !r.recording(); }));
  }
  std::size_t images = 0;
  for (int k = 0; k < 6; ++k) {
    const std::string part = dir + "/parts_" + std::to_string(k) + ".bag";
    ASSERT_TRUE(fs::exists(part)) << part;
    const auto in_part = readTopic<sensor_msgs::Image>(part, "/camera/image_raw");
    ASSERT_EQ(in_part.size(), 1u);  // a frame is never split over two files
    EXPECT_EQ(in_part[0].first, frameTime(k));
    EXPECT_EQ(readTopic<sensor_msgs::PointCloud2>(part, "/camera/points").size(), 1u);
    images += in_part.size();
  }
  EXPECT_EQ(images, 6u);
  EXPECT_FALSE(fs::exists(dir + "/parts_6.bag"));
  EXPECT_FALSE(fs::exists(dir + "/parts.bag"));
}

TEST(BagWriter, StopClosesTheFileAndStartRecordsANewOne) {
  const std::string out = fresh("start_stop") + "/values.bag";
  Graph g(pluginRegistry());
  feedRecorder(g, "[/value]", out, "value");
  auto* feeder = object<MessageFeeder>(g, "feed");
  auto written = [&](std::size_t n) {  // the file holds n values once closed
    // read once it is closed (renamed): rosbag's encryptor plugin is loaded and unloaded by each
    // open and close, and the recorder's close must not meet this test's open (pluginlib crashes)
    return waitUntil([&] { return fs::exists(out) && !fs::exists(out + ".active"); }) &&
           readTopic<std_msgs::Int32>(out, "/value").size() == n;
  };
  for (int v : {1, 2, 3}) feeder->feed(Message::make<int>(v));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_FALSE(fs::exists(out));  // still being written
  EXPECT_TRUE(fs::exists(out + ".active"));
  ASSERT_TRUE(g.fireSlot("rec", "stop"));
  ASSERT_TRUE(written(3));
  const auto values = readTopic<std_msgs::Int32>(out, "/value");
  EXPECT_EQ(values[2].second->data, 3);
  const ros::Time now = ros::Time::now();  // no header: recorded at the clock's time
  EXPECT_NEAR((now - values[2].first).toSec(), 0.0, 60.0);
  EXPECT_LE(values[0].first, values[2].first);

  feeder->feed(Message::make<int>(4));  // stopped: not recorded
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_FALSE(fs::exists(out + ".active"));
  ASSERT_TRUE(g.fireSlot("rec", "start"));
  feeder->feed(Message::make<int>(5));
  ASSERT_TRUE(g.waitIdle(kWait));
  set(g, "rec", "recording", "false");  // as the stop slot does
  ASSERT_TRUE(written(1));
  EXPECT_EQ(readTopic<std_msgs::Int32>(out, "/value")[0].second->data, 5);
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(BagWriter, ABagItDidNotRecordIsLeftAsItIsUnlessOverwriteSaysSo) {
  const std::string dir = fresh("not_ours");
  const std::string out = dir + "/run3.bag", unfinished = dir + "/crashed.bag";
  std::ofstream(out) << "the user's own bag";
  std::ofstream(unfinished + ".active") << "what a crashed recording left";
  Graph g(pluginRegistry());
  feedRecorder(g, "[/value]", out, "value");
  auto* feeder = object<MessageFeeder>(g, "feed");
  feeder->feed(Message::make<int>(1));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_THAT(errorOf(g, "rec"), HasSubstr("'" + out +
                                           "' exists (not recorded by this node): left as it is; set "
                                           "'overwrite' to replace it, or choose another file"));
  set(g, "rec", "file", unfinished);
  feeder->feed(Message::make<int>(2));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_THAT(errorOf(g, "rec"), HasSubstr("a recording that did not finish (rosbag reindex recovers it)"));
  EXPECT_EQ(readFile(out), "the user's own bag");
  EXPECT_EQ(readFile(unfinished + ".active"), "what a crashed recording left");

  set(g, "rec", "file", out);
  set(g, "rec", "overwrite", "true");  // the user says so
  feeder->feed(Message::make<int>(3));
  ASSERT_TRUE(g.waitIdle(kWait));
  ASSERT_TRUE(g.fireSlot("rec", "stop"));
  ASSERT_TRUE(waitUntil([&] { return !fs::exists(out + ".active"); }));
  EXPECT_EQ(errorOf(g, "rec"), "");
  EXPECT_EQ(readTopic<std_msgs::Int32>(out, "/value").at(0).second->data, 3);
  set(g, "rec", "overwrite", "false");  // its own recording: start records it anew all the same
  ASSERT_TRUE(g.fireSlot("rec", "start"));
  feeder->feed(Message::make<int>(4));
  ASSERT_TRUE(g.waitIdle(kWait));
  ASSERT_TRUE(g.fireSlot("rec", "stop"));
  ASSERT_TRUE(waitUntil([&] { return !fs::exists(out + ".active"); }));
  EXPECT_EQ(errorOf(g, "rec"), "");
  EXPECT_EQ(readTopic<std_msgs::Int32>(out, "/value").at(0).second->data, 4);
}

apex::Message stampedImage(int k) {
  apex_nodes::Image i;
  i.header.stamp = frameTime(k);
  i.encoding = "mono8";
  i.mat = cv::Mat(2, 3, CV_8UC1, cv::Scalar(k));
  return Message::make<apex_nodes::Image>(i);
}

TEST(BagWriter, AFrameSentAgainIsRecordedOnceAndChangingTheSplitSizeLosesNothing) {
  const std::string dir = fresh("held");
  Graph g(pluginRegistry());
  feedRecorder(g, "[/camera/image_raw]", dir + "/parts.bag", "camera_image_raw");
  set(g, "rec", "split_size", "1");  // 1 MB: frame 0 stays in the open part
  auto* feed = object<MessageFeeder>(g, "feed");
  feed->feed(stampedImage(0));
  feed->feed(stampedImage(0));  // a held frame, sent again
  ASSERT_TRUE(g.waitIdle(kWait));
  set(g, "rec", "split_size", "0.002");  // closes part 0 as it is; frame 1 goes to part 1
  feed->feed(stampedImage(1));
  ASSERT_TRUE(g.waitIdle(kWait));
  set(g, "rec", "recording", "false");
  ASSERT_TRUE(waitUntil([&] { return fs::exists(dir + "/parts_1.bag") && !fs::exists(dir + "/parts_1.bag.active"); }));
  const auto first = readTopic<sensor_msgs::Image>(dir + "/parts_0.bag", "/camera/image_raw");
  const auto second = readTopic<sensor_msgs::Image>(dir + "/parts_1.bag", "/camera/image_raw");
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].first, frameTime(0));
  ASSERT_EQ(second.size(), 1u);
  EXPECT_EQ(second[0].first, frameTime(1));
  EXPECT_EQ(errorOf(g, "rec"), "");
}

TEST(BagWriter, ATypeWithNoRosMessageIsAnErrorOnTheNodeAndNothingIsWritten) {
  const std::string out = fresh("no_ros_type") + "/regions.bag";
  Graph g(pluginRegistry());
  feedRecorder(g, "[/regions]", out, "regions");
  object<MessageFeeder>(g, "feed")->feed(Message::make<NoRosForm>({}));
  ASSERT_TRUE(waitUntil([&] { return !errorOf(g, "rec").empty(); }));
  EXPECT_THAT(errorOf(g, "rec"), HasSubstr("input 'regions' carries test/NoRosForm, which has no ROS message to record"));
  EXPECT_THAT(errorOf(g, "rec"), HasSubstr("apex_nodes/Regions"));  // among the types that have one
  EXPECT_FALSE(fs::exists(out + ".active"));
  auto twice = g.setParameter("rec", "topics", "[/a/b, /a_b]");
  ASSERT_FALSE(twice);
  EXPECT_THAT(twice.message(), HasSubstr("topics '/a/b' and '/a_b' both make input 'a_b'"));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::Time::init();
  return RUN_ALL_TESTS();
}
