// BagReader as a player: outputs per topic, one firing per frame, seek, restart,
// a held frame sent again on a change downstream; any message type; on bags this test writes.
#include <gmock/gmock.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/view.h>
#include <sensor_msgs/Imu.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>

#include "apex_nodes/ros_message.hpp"
#include "apex_nodes/types.hpp"
#include "apex_test/node_harness.hpp"
#include "apex_test/test_bags.hpp"

using namespace apex_test;
using testing::ElementsAre;
using testing::HasSubstr;

namespace {

/** bag → image, cloud, frame and stamp collectors; `finished` → a counter's reset slot. */
class Player {
 public:
  explicit Player(int frames, const std::string& extra = "") : g_(pluginRegistry()) {
    auto added = g_.addNode(description(writeBag(frames), extra));
    EXPECT_TRUE(added) << added.message();
    for (const char* sink : {"images", "clouds", "frames", "stamps"}) add(g_, "test/Collector", sink);
    add(g_, "test/Counter", "passes");
    add(g_, "apex_nodes/SequenceMean", "per_pass");  // counts the frames of a pass, at its end
    add(g_, "test/Collector", "pass_lengths");
    link(g_, "bag", "camera_image_raw", "images", "in");
    link(g_, "bag", "camera_points", "clouds", "in");
    link(g_, "bag", "frame", "frames", "in");
    link(g_, "bag", "stamp", "stamps", "in");
    link(g_, "bag", "finished", "passes", "reset");
    link(g_, "bag", "stamp", "per_pass", "value");
    link(g_, "per_pass", "count", "pass_lengths", "in");
    g_.start();
  }
  static NodeDescription description(const std::string& file, const std::string& extra) {
    NodeDescription d;
    d.name = "bag", d.type = "apex_nodes/BagReader";
    d.parameters = {{"file", file}, {"topics", "[/camera/image_raw, /camera/points]"}, {"rate", "0"}};
    d.interactive = {"frame"};  // its output: the index of each frame sent
    if (!extra.empty()) d.parameters.emplace_back(extra.substr(0, extra.find('=')), extra.substr(extra.find('=') + 1));
    return d;
  }
  Graph& graph() { return g_; }
  Collector& sink(const std::string& name) { return *object<Collector>(g_, name); }
  void set(const std::string& param, const std::string& value) {
    auto r = g_.setParameter("bag", param, value);
    ASSERT_TRUE(r) << r.message();
  }
  std::vector<double> stamps() {
    std::vector<double> out;
    for (const auto& m : sink("stamps").messages()) out.push_back(m.isNothing() ? -1 : *m.as<double>());
    return out;
  }
  /** The stamps of the frames sent (a wake-up with nothing to send sends Nothing). */
  std::vector<double> sent() {
    std::vector<double> out;
    for (double t : stamps())
      if (t >= 0) out.push_back(t);
    return out;
  }

 private:
  Graph g_;
};

TEST(BagReader, OneOutputPerTopicTypedByItsMessageType) {
  Player p(3, "playing=false");
  const auto iface = p.graph().nodeInterface("bag");
  ASSERT_TRUE(iface);
  ASSERT_EQ(iface->outputs.size(), 3u);  // + stamp
  EXPECT_EQ(iface->outputs[0].name, "camera_image_raw");
  EXPECT_EQ(iface->outputs[0].type, typeOf<apex_nodes::Image>());
  EXPECT_EQ(iface->outputs[1].name, "camera_points");
  EXPECT_EQ(iface->outputs[1].type, typeOf<apex_nodes::Cloud>());
  // Fewer topics: the output of the one that goes loses its connection, the rest stays.
  p.set("topics", "[/camera/image_raw]");
  for (const auto& c : p.graph().describe().connections) EXPECT_NE(c.from_port, "camera_points");
  // Any other type: the library's port type for it (std_msgs/String: a string), else the ROS
  // message itself (test_any_topic plays nav_msgs/Odometry).
  p.set("topics", "[/camera/image_raw, /notes]");
  EXPECT_EQ(p.graph().nodeInterface("bag")->outputs[1].type, typeOf<std::string>());
  EXPECT_EQ(p.graph().nodeInterface("bag")->outputs[1].description, "messages of /notes (std_msgs/String)");
}

TEST(BagReader, CameraInfoTopicsPlayAsCameraModelsBesideTheirImages) {
  Graph g(pluginRegistry());
  NodeDescription d = Player::description(writeBag(3), "");
  d.parameters = {{"file", writeBag(3)}, {"topics", "[/camera/image_raw, /camera/camera_info]"}, {"rate", "0"}};
  ASSERT_TRUE(g.addNode(d));
  EXPECT_EQ(g.nodeInterface("bag")->outputs[1].type, typeOf<sensor_msgs::CameraInfo>());
  add(g, "test/Collector", "images"), add(g, "test/Collector", "models");
  link(g, "bag", "camera_image_raw", "images", "in");
  link(g, "bag", "camera_camera_info", "models", "in");
  g.start();
  ASSERT_TRUE(object<Collector>(g, "models")->waitFor(3));
  ASSERT_TRUE(object<Collector>(g, "images")->waitFor(3));
  const auto models = object<Collector>(g, "models")->messages();
  const auto images = object<Collector>(g, "images")->messages();
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(models[k].as<sensor_msgs::CameraInfo>());
    ASSERT_TRUE(images[k].as<apex_nodes::Image>());
    EXPECT_EQ(models[k].as<sensor_msgs::CameraInfo>()->K, cameraInfo(k).K);
    EXPECT_EQ(models[k].as<sensor_msgs::CameraInfo>()->header.stamp, images[k].as<apex_nodes::Image>()->header.stamp);
  }
}

TEST(BagReader, TheMessagesOfAFrameLeaveInOneFiringAndFinishedFiresOncePerPass) {
  Player p(40);
  ASSERT_TRUE(p.sink("stamps").waitFor(40));
  ASSERT_TRUE(p.graph().waitIdle(kWait));
  ASSERT_TRUE(object<Counter>(p.graph(), "passes")->resets == 1);
  // the end of the pass follows its last frame: all 40 are counted before it
  EXPECT_EQ(p.sink("pass_lengths").ints().back(), 40);
  for (const char* sink : {"images", "clouds", "stamps"}) {  // frame: a parameter output, it never holds the player
    SCOPED_TRACE(sink);
    const auto got = p.sink(sink).messages();
    EXPECT_EQ(got.size(), 40u);  // one firing per frame...
    EXPECT_EQ(std::count_if(got.begin(), got.end(), [](const Message& m) { return m.isNothing(); }), 0);  // ...with all of it
  }
  EXPECT_EQ(p.sink("frames").ints().back(), 39);
  EXPECT_EQ(std::get<int>(p.graph().parameterValue("bag", "frame").value()), 39);  // the position shows
  ASSERT_TRUE(p.graph().fireSlot("bag", "restart"));  // replays from frame 0
  ASSERT_TRUE(p.sink("stamps").waitFor(80));
  ASSERT_TRUE(p.graph().waitIdle(kWait));
  EXPECT_EQ(p.stamps()[40], frameTime(0).toSec());
  EXPECT_EQ(object<Counter>(p.graph(), "passes")->resets, 2);
}

TEST(BagReader, RestampStampsEachFrameWithTheTimeItIsSentSoLatenciesAreLive) {
  const auto wall = [] {
    const ros::WallTime w = ros::WallTime::now();
    return ros::Time(w.sec, w.nsec);
  };
  const auto latencyFrames = [](const Graph& g) {
    for (const auto& s : g.nodeStats(1e9))
      if (s.name == "bag") return s.latency_frames;
    return std::uint64_t{99};
  };
  {  // the recorded stamps: from long ago, no latency
    Player p(3);
    ASSERT_TRUE(p.sink("images").waitFor(3));
    ASSERT_TRUE(p.graph().waitIdle(kWait));
    EXPECT_EQ(p.sink("images").messages()[0].as<apex_nodes::Image>()->header.stamp, frameTime(0));
    EXPECT_EQ(latencyFrames(p.graph()), 0u);
  }
  const ros::Time before = wall();
  Player p(3, "restamp=true");
  ASSERT_TRUE(p.sink("images").waitFor(3));
  ASSERT_TRUE(p.graph().waitIdle(kWait));
  const ros::Time after = wall();
  ros::Time last;
  for (const Message& m : p.sink("images").messages()) {
    const ros::Time t = m.as<apex_nodes::Image>()->header.stamp;
    EXPECT_GE(t, before);
    EXPECT_LE(t, after);
    EXPECT_GE(t, last) << "in the order sent";
    last = t;
  }
  EXPECT_EQ(p.stamps()[0], frameTime(0).toSec()) << "`stamp` still tells the record time";
  EXPECT_EQ(latencyFrames(p.graph()), 3u) << "each frame's latency is live";
}

TEST(BagReader, EndPassEndsThePassAfterTheFramesSentAndTheNextBagPlaysFromItsStart) {
  Player p(200, "rate=1");  // 200 frames at the recorded pace: the pass is cut long before its end
  const auto sent = [&] { return p.sent(); };
  ASSERT_TRUE(waitUntil([&] { return sent().size() >= 3; }));
  ASSERT_TRUE(p.graph().fireSlot("bag", "end_pass"));
  ASSERT_TRUE(waitUntil([&] { return object<Counter>(p.graph(), "passes")->resets == 1; })) << "finished, as at an end";
  ASSERT_TRUE(p.graph().waitIdle(kWait));
  const std::size_t cut_at = sent().size();
  EXPECT_LT(cut_at, 100u);
  ASSERT_FALSE(p.sink("pass_lengths").ints().empty());
  EXPECT_EQ(p.sink("pass_lengths").ints().back(), static_cast<int>(cut_at)) << "every frame sent is in the pass, then its end";
  EXPECT_EQ(std::get<int>(p.graph().parameterValue("bag", "frame").value()), 199) << "at the end, as if played through";
  ASSERT_TRUE(p.graph().fireSlot("bag", "end_pass"));  // no pass in progress: nothing happens
  add(p.graph(), "test/Gain", "gain");
  link(p.graph(), "bag", "frame", "gain", "in");  // an edit downstream: the frame held, sent again, is the last
  ASSERT_TRUE(waitUntil([&] { return sent().size() == cut_at + 1; }));
  EXPECT_EQ(sent().back(), frameTime(199).toSec());
  p.set("rate", "0");
  p.set("file", writeBag(50));
  ASSERT_TRUE(waitUntil([&] { return sent().size() == cut_at + 1 + 50; }));
  ASSERT_TRUE(p.graph().waitIdle(kWait));
  EXPECT_EQ(sent()[cut_at + 1], frameTime(0).toSec()) << "another bag plays from its start, not from where the pass was cut";
  EXPECT_EQ(object<Counter>(p.graph(), "passes")->resets, 2);
}

TEST(BagReader, SeekingSendsExactlyTheFramesAskedFor) {
  Player p(40, "playing=false");
  int n = 0;
  for (int k : {0, 39, 17}) {
    p.set("frame", std::to_string(k));
    ASSERT_TRUE(p.sink("stamps").waitFor(++n));
  }
  ASSERT_TRUE(p.graph().waitIdle(kWait));
  EXPECT_THAT(p.stamps(), ElementsAre(frameTime(0).toSec(), frameTime(39).toSec(), frameTime(17).toSec()));
  EXPECT_EQ(p.sink("frames").ints().back(), 17);
  p.set("time", "1.75");  // by time: the first frame at or after 1.75 s into the bag
  ASSERT_TRUE(p.sink("stamps").waitFor(4));
  ASSERT_TRUE(p.graph().waitIdle(kWait));
  EXPECT_EQ(p.stamps().back(), frameTime(18).toSec());
  EXPECT_EQ(std::get<int>(p.graph().parameterValue("bag", "frame").value()), 18);
  p.set("frame", "17");
  ASSERT_TRUE(p.sink("stamps").waitFor(5));
  auto past = p.graph().setParameter("bag", "frame", "40");  // the parameter's range is the bag's frames
  ASSERT_FALSE(past);
  EXPECT_EQ(past.message(), "node 'bag': parameter 'frame': 40 is out of range [0, 39]");
  ASSERT_TRUE(p.graph().fireSlot("bag", "previous"));
  ASSERT_TRUE(p.graph().fireSlot("bag", "previous"));
  ASSERT_TRUE(p.graph().fireSlot("bag", "next"));
  ASSERT_TRUE(p.sink("stamps").waitFor(6));
  ASSERT_TRUE(p.graph().waitIdle(kWait));
  const auto got = p.stamps();  // presses in quick succession add up and may be sent as one
  EXPECT_EQ(got.back(), frameTime(16).toSec());
  EXPECT_LE(got.size(), 8u);
  for (std::size_t i = 5; i < got.size(); ++i) EXPECT_THAT(got[i], testing::AnyOf(frameTime(16).toSec(), frameTime(15).toSec()));
}

TEST(BagReader, AHeldFrameIsSentAgainWhenSomethingDownstreamChanges) {
  Player p(40, "playing=false");
  add(p.graph(), "test/Gain", "gain");
  add(p.graph(), "test/Collector", "gained");
  link(p.graph(), "bag", "frame", "gain", "in");
  link(p.graph(), "gain", "out", "gained", "in");
  p.set("frame", "7");
  ASSERT_TRUE(p.sink("frames").waitFor(1));
  ASSERT_TRUE(p.graph().waitIdle(kWait));
  ASSERT_EQ(p.stamps().size(), 1u);
  ASSERT_TRUE(p.graph().setParameter("gain", "gain", "3"));  // no play, no step
  ASSERT_TRUE(p.sink("stamps").waitFor(2));
  ASSERT_TRUE(p.graph().waitIdle(kWait));
  EXPECT_EQ(p.stamps().back(), frameTime(7).toSec());
  EXPECT_EQ(object<Collector>(p.graph(), "gained")->ints().back(), 21);

  // 20 changes at once: runs on frame 7 only, the last with the last value.
  for (int v = 1; v <= 20; ++v) ASSERT_TRUE(p.graph().setParameter("gain", "gain", std::to_string(v)));
  auto& gained = *object<Collector>(p.graph(), "gained");
  while (gained.ints().back() != 7 * 20 && gained.waitFor(gained.size() + 1)) {
  }  // the last re-run comes at most one pass after the last change
  EXPECT_EQ(gained.ints().back(), 7 * 20);
  ASSERT_TRUE(p.graph().waitIdle(kWait));
  EXPECT_LE(p.stamps().size(), 2u + 20u);
  for (double t : p.stamps()) EXPECT_EQ(t, frameTime(7).toSec());
}

TEST(BagReader, WithoutRerunsOnEditsAHeldFrameIsNotSentAgain) {
  // The Optimizer's copies replay whole passes and set each candidate by edits: the last frame,
  // held at the end of a pass, sent again would be counted into the next pass (Graph::setRerunOnEdit).
  Graph g(pluginRegistry());
  g.setRerunOnEdit(false);  // first, as the copies do: no re-run of an earlier edit is pending either
  ASSERT_TRUE(g.addNode(Player::description(writeBag(40), "")));
  add(g, "test/Collector", "stamps");
  add(g, "test/Gain", "gain");
  link(g, "bag", "stamp", "stamps", "in");
  link(g, "bag", "frame", "gain", "in");
  g.start();
  auto& stamps = *object<Collector>(g, "stamps");
  const auto sent = [&] {  // frames, not the Nothing of a wake-up with nothing to send
    const auto got = stamps.messages();
    return std::count_if(got.begin(), got.end(), [](const Message& m) { return !m.isNothing(); });
  };
  ASSERT_TRUE(waitUntil([&] { return sent() == 40; }));
  ASSERT_TRUE(g.waitIdle(kWait));
  for (int v = 1; v <= 5; ++v) ASSERT_TRUE(g.setParameter("gain", "gain", std::to_string(v)));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_FALSE(waitUntil([&] { return sent() > 40; }, 0.6)) << "the held frame went out again";
  g.setRerunOnEdit(true);  // as by default: the next edit shows on the held frame
  ASSERT_TRUE(g.setParameter("gain", "gain", "6"));
  EXPECT_TRUE(waitUntil([&] { return sent() == 41; }));
}

TEST(BagReader, AtTheEndOfAPassTheLastFrameIsHeldAndANodeConnectedAfterGetsIt) {
  Player p(5);  // plays once (no loop, as rosbag play) and stops on frame 4
  ASSERT_TRUE(p.sink("stamps").waitFor(5));
  ASSERT_TRUE(p.graph().waitIdle(kWait));
  ASSERT_EQ(object<Counter>(p.graph(), "passes")->resets, 1);
  // a node added after the pass: it gets the held frame, not "waiting for a frame"
  add(p.graph(), "test/Gain", "gain");
  add(p.graph(), "test/Collector", "gained");
  link(p.graph(), "gain", "out", "gained", "in");
  link(p.graph(), "bag", "frame", "gain", "in");
  ASSERT_TRUE(object<Collector>(p.graph(), "gained")->waitFor(1));
  EXPECT_EQ(object<Collector>(p.graph(), "gained")->ints().back(), 4);
  ASSERT_TRUE(p.graph().setParameter("gain", "gain", "3"));  // tuned after the pass: the same frame again
  auto& gained = *object<Collector>(p.graph(), "gained");
  while (gained.ints().back() != 12 && gained.waitFor(gained.size() + 1)) {
  }
  EXPECT_EQ(gained.ints().back(), 12);
  ASSERT_TRUE(p.graph().waitIdle(kWait));
  for (std::size_t i = 5; i < p.stamps().size(); ++i) EXPECT_EQ(p.stamps()[i], frameTime(4).toSec());
  EXPECT_EQ(object<Counter>(p.graph(), "passes")->resets, 1);  // re-sending ends no pass
}

TEST(BagReader, GraphsWithTheOlderParametersStillLoad) {
  Graph g(pluginRegistry());
  NodeDescription d;
  d.name = "bag", d.type = "apex_nodes/BagReader";
  d.parameters = {{"file", writeBag(5)}, {"image_topic", "/camera/image_raw"}, {"cloud_topic", "/camera/points"}, {"rate", "0"}};
  ASSERT_TRUE(g.addNode(d));
  add(g, "test/Collector", "images");
  add(g, "test/Collector", "clouds");
  link(g, "bag", "image", "images", "in");
  link(g, "bag", "cloud", "clouds", "in");
  g.start();
  ASSERT_TRUE(object<Collector>(g, "clouds")->waitFor(5));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(object<Collector>(g, "images")->size(), 5u);  // one firing per frame here too
}

TEST(BagReader, AMissingBagLeavesOutputsThatCarryAnythingAndSaysWhy) {
  Graph g(pluginRegistry());
  NodeDescription d;
  d.name = "bag", d.type = "apex_nodes/BagReader";
  d.parameters = {{"file", "/nonexistent/x.bag"}, {"topics", "[/camera/image_raw]"}};
  ASSERT_TRUE(g.addNode(d));
  EXPECT_EQ(g.nodeInterface("bag")->outputs[0].type, typeOf<Any>());
  g.start();
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_THAT(g.nodeStats(0).at(0).error, HasSubstr("cannot open bag '/nonexistent/x.bag': no such file"));
  // pressing play or next does not make it look fine: it stays in error until a file opens
  ASSERT_TRUE(g.setParameter("bag", "playing", "false"));
  ASSERT_TRUE(g.waitIdle(kWait));  // two values set at once would apply as one: no change
  ASSERT_TRUE(g.setParameter("bag", "playing", "true"));
  ASSERT_TRUE(g.fireSlot("bag", "next"));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_THAT(g.nodeStats(0).at(0).error, HasSubstr("cannot open bag '/nonexistent/x.bag': no such file"));
  ASSERT_TRUE(g.setParameter("bag", "file", writeBag(3)));
  ASSERT_TRUE(waitUntil([&] { return g.nodeStats(0).at(0).error.empty(); }));
}

TEST(BagReader, ABagSwitchedToAMissingFileStaysInErrorWhilePlaying) {
  Graph g(pluginRegistry());
  NodeDescription d;
  d.name = "bag", d.type = "apex_nodes/BagReader";
  d.parameters = {{"file", writeBag(3)}, {"image_topic", "/camera/image_raw"}, {"loop", "true"}, {"rate", "50"}};
  ASSERT_TRUE(g.addNode(d));
  add(g, "test/Collector", "images");
  link(g, "bag", "image", "images", "in");
  g.start();
  ASSERT_TRUE(object<Collector>(g, "images")->waitFor(2));
  (void)g.setParameter("bag", "file", "/nonexistent/y.bag");  // the node says why, and keeps saying it
  ASSERT_TRUE(waitUntil([&] { return !g.nodeStats(0).at(0).error.empty(); }));
  ASSERT_TRUE(g.setParameter("bag", "playing", "false"));
  ASSERT_TRUE(g.waitIdle(kWait));  // two values set at once would apply as one: no change
  ASSERT_TRUE(g.setParameter("bag", "playing", "true"));
  ASSERT_TRUE(g.fireSlot("bag", "next"));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_THAT(g.nodeStats(0).at(0).error, HasSubstr("cannot open bag '/nonexistent/y.bag'"));
}

nav_msgs::Odometry odometry(int k) {
  nav_msgs::Odometry o;
  o.header.stamp = frameTime(k) + ros::Duration(0.25);
  o.header.frame_id = "odom";
  o.pose.pose.position.x = 1.5 + k;
  o.twist.covariance[35] = k;
  return o;
}

sensor_msgs::Imu imu(int k) {
  sensor_msgs::Imu m;
  m.header.stamp = frameTime(k);
  m.linear_acceleration.z = 9.81 + k;
  return m;
}

/** A bag of `frames` frames of nav_msgs/Odometry on /odom and, 2 ms later, sensor_msgs/Imu on /imu. */
std::string writeOdometryBag(int frames) {
  const std::string path = (bagDirectory() / ("odometry_" + std::to_string(frames) + ".bag")).string();
  if (std::filesystem::exists(path)) return path;
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  for (int k = 0; k < frames; ++k) {
    bag.write("/odom", frameTime(k), odometry(k));
    bag.write("/imu", frameTime(k) + ros::Duration(0.002), imu(k));
  }
  return path;
}

/** bag /odom, /imu → FieldExtract of the odometry's x, a collector of the IMU's messages, and a BagWriter of both. */
void playAndRecord(Graph& g, const std::string& out) {
  add(g, "apex_nodes/BagReader", "bag");
  ASSERT_TRUE(g.setParameter("bag", "topics", "[/odom, /imu]"));
  ASSERT_TRUE(g.setParameter("bag", "rate", "0"));
  ASSERT_TRUE(g.setParameter("bag", "file", writeOdometryBag(3)));
  add(g, "apex_nodes/BagWriter", "rec");
  ASSERT_TRUE(g.setParameter("rec", "topics", "[/odom, /imu]"));
  ASSERT_TRUE(g.setParameter("rec", "file", out));
  add(g, "apex_nodes/FieldExtract", "x");
  ASSERT_TRUE(g.setParameter("x", "field", "pose.pose.position.x"));
  add(g, "test/Collector", "xs"), add(g, "test/Collector", "imus");
  for (const char* topic : {"odom", "imu"}) link(g, "bag", topic, "rec", topic);
  link(g, "bag", "odom", "x", "message");
  link(g, "x", "value", "xs", "in");
  link(g, "bag", "imu", "imus", "in");
  g.start();
}

TEST(BagReader, AnyTypePlaysAsTheRosMessageAndBagWriterRecordsItAsItWas) {
  const auto dir = bagDirectory() / "any_type";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string out = (dir / "out.bag").string();
  {
    Graph g(pluginRegistry());
    playAndRecord(g, out);
    EXPECT_EQ(g.nodeInterface("bag")->outputs[0].type, typeOf<apex_nodes::RosMessage>());
    EXPECT_EQ(g.nodeInterface("bag")->outputs[1].type, typeOf<apex_nodes::RosMessage>());
    auto& xs = *object<Collector>(g, "xs");
    auto& imus = *object<Collector>(g, "imus");
    ASSERT_TRUE(xs.waitFor(3) && imus.waitFor(3));
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(xs.messages()[k].as<double>()) << "FieldExtract sent no number";
      EXPECT_EQ(*xs.messages()[k].as<double>(), 1.5 + k);
      ASSERT_TRUE(imus.messages()[k].as<apex_nodes::RosMessage>());
      EXPECT_EQ(*imus.messages()[k].as<apex_nodes::RosMessage>(), apex_nodes::toRosMessage(imu(k)));  // as it was
    }
    // the pass's end stops the recording: the file has its name once closed
    ASSERT_TRUE(waitUntil([&] { return std::filesystem::exists(out) && !std::filesystem::exists(out + ".active"); }));
  }
  rosbag::Bag bag(out, rosbag::bagmode::Read);
  int k = 0;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/odom"))) {
    EXPECT_EQ(m.getDataType(), "nav_msgs/Odometry");
    EXPECT_EQ(m.getTime(), odometry(k).header.stamp);  // recorded at its header's stamp
    const auto read = m.instantiate<nav_msgs::Odometry>();
    ASSERT_TRUE(read);
    EXPECT_EQ(*read, odometry(k++));
  }
  EXPECT_EQ(k, 3);
}

/** Median wall time from setting `frame` to that frame's stamp arriving. */
double seekSeconds(Player& p, int k, int repeats) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    for (int target : {k == 1 ? 2 : 1, k}) {  // away first: every set is a change
      const auto before = p.sink("stamps").size();
      const auto start = std::chrono::steady_clock::now();
      p.set("frame", std::to_string(target));
      EXPECT_TRUE(p.sink("stamps").waitFor(before + 1));
      if (target == k) t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      EXPECT_TRUE(p.graph().waitIdle(kWait));
    }
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

TEST(BagReader, SeekingToTheLastOfTenThousandFramesCostsWhatSeekingToTheFirstDoes) {
  Player p(10000, "playing=false");
  const double first = seekSeconds(p, 0, 21), last = seekSeconds(p, 9999, 21);
  std::printf("seek on 10,000 frames: first %.3f ms, last %.3f ms\n", first * 1e3, last * 1e3);
  // Replaying from the start would take ~10,000 times longer: a bound far from both, whatever the
  // machine's load between the two medians (the figures are bench/player_bench.cpp's).
  EXPECT_LT(last, 20 * first + 0.05);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::Time::init();
  return RUN_ALL_TESTS();
}
