// Tuning on a held frame, as a user does it with rosservice or the panel: the
// demo graph's player is paused; seeking sends exactly the frames asked for;
// setting the threshold's `c` re-runs the held frame at once (no play, no step);
// a burst of changes re-runs it a few times, the last with the last value; whoever
// watches one of its ports (a display, a preview) gets the held frame at once.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <apex/Control.h>
#include <apex/Inspect.h>
#include <apex/RuntimeStatus.h>
#include <apex/SetParameter.h>
#include <sensor_msgs/Image.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <thread>

#include "apex_test/ros_client.hpp"

using namespace apex_test;
using Clock = std::chrono::steady_clock;

namespace {

std::string g_bag;

/** Every overlay that arrives, with its arrival time. */
class Overlays {
 public:
  explicit Overlays(ros::NodeHandle& nh)
      : sub_(nh.subscribe<sensor_msgs::Image>("/apex_demo/overlay", 50, [this](const sensor_msgs::Image::ConstPtr& m) {
          std::lock_guard<std::mutex> l(m_);
          got_.push_back({Clock::now(), m});
          cv_.notify_all();
        })) {}
  /** Until the runtime's publisher is connected (roscpp has no callback for this: polled, 30 s at most). */
  bool waitConnected() const {
    const auto deadline = Clock::now() + std::chrono::seconds(30);
    while (sub_.getNumPublishers() == 0 && Clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return sub_.getNumPublishers() > 0;
  }
  std::size_t size() {
    std::lock_guard<std::mutex> l(m_);
    return got_.size();
  }
  /** The next overlay after the first `after`, or nullptr after 10 s. */
  std::pair<Clock::time_point, sensor_msgs::Image::ConstPtr> next(std::size_t after) {
    std::unique_lock<std::mutex> l(m_);
    if (!cv_.wait_for(l, std::chrono::seconds(10), [&] { return got_.size() > after; })) return {};
    return got_[after];
  }
  std::vector<sensor_msgs::Image::ConstPtr> since(std::size_t after) {
    std::lock_guard<std::mutex> l(m_);
    std::vector<sensor_msgs::Image::ConstPtr> out;
    for (std::size_t i = after; i < got_.size(); ++i) out.push_back(got_[i].second);
    return out;
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  std::vector<std::pair<Clock::time_point, sensor_msgs::Image::ConstPtr>> got_;
  ros::Subscriber sub_;
};

void set(const std::string& node, const std::string& param, const std::string& value) {
  apex::SetParameter::Request r;
  r.node = node, r.parameter = param, r.value = value;
  auto res = call<apex::SetParameter>("set_parameter", r);
  ASSERT_TRUE(res.success) << node << "/" << param << ": " << res.message;
}

/** The image stamps of the bag, frame by frame. */
std::vector<ros::Time> bagStamps() {
  rosbag::Bag bag(g_bag);
  std::vector<ros::Time> out;
  for (const auto& m : rosbag::View(bag, rosbag::TopicQuery("/camera/image_raw")))
    out.push_back(m.instantiate<sensor_msgs::Image>()->header.stamp);
  return out;
}

/** Until the graph is quiet: two ~status messages in a row (0.5 s apart) with the same overlay firings. */
bool quiet(ros::NodeHandle& nh) {
  std::uint64_t last = firingsOf(nh, "overlay");
  for (int i = 0; i < 20; ++i) {
    const std::uint64_t now = firingsOf(nh, "overlay");
    if (now == last) return true;
    last = now;
  }
  return false;
}

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

bool sameImage(const sensor_msgs::Image& a, const sensor_msgs::Image& b) {
  return a.width == b.width && a.height == b.height && a.data == b.data;
}

TEST(HeldFrame, SeekThenTuneOnTheHeldFrameWithoutPlaying) {
  ros::NodeHandle nh;
  Overlays overlays(nh);
  ASSERT_TRUE(overlays.waitConnected()) << "the overlay publisher never connected";
  const auto stamps = bagStamps();
  ASSERT_EQ(stamps.size(), 40u);

  // Seek: exactly the frames asked for, in order. The time it takes is the pipeline's own.
  std::vector<double> pipeline;
  for (int k : {0, 39, 17, 7}) {
    const auto before = overlays.size();
    const auto start = Clock::now();
    set("bag", "frame", std::to_string(k));
    auto [when, image] = overlays.next(before);
    ASSERT_TRUE(image) << "no overlay after seeking to frame " << k;
    EXPECT_EQ(image->header.stamp, stamps[k]) << "seek to frame " << k;
    pipeline.push_back(seconds(when - start));
  }
  std::sort(pipeline.begin(), pipeline.end());
  const double processing = pipeline.back();

  // A parameter change re-runs the held frame 7, at once.
  const auto before = overlays.size();
  const auto start = Clock::now();
  set("threshold", "c", "10.0");
  auto [when, image] = overlays.next(before);
  ASSERT_TRUE(image) << "setting threshold/c on a paused player sent no new overlay";
  EXPECT_EQ(image->header.stamp, stamps[7]);
  // at once: not after a pass or a play tick (seconds); the time itself is the benchmark's
  std::printf("re-run after a change: %.1f ms; pipeline %.1f ms\n", seconds(when - start) * 1e3, processing * 1e3);
  EXPECT_LT(seconds(when - start), processing + 5.0) << "pipeline " << processing << " s";

  // 20 changes within 50 ms: a few re-runs, all of frame 7, the last with the last value.
  // A persistent connection, as a slider's client keeps: a call then takes about a millisecond.
  auto client = nh.serviceClient<apex::SetParameter>(service("set_parameter"), true);
  apex::SetParameter burst_call;
  burst_call.request.node = "threshold", burst_call.request.parameter = "c", burst_call.request.value = "25.0";
  const auto connected = overlays.size();
  ASSERT_TRUE(client.call(burst_call) && burst_call.response.success);
  ASSERT_TRUE(overlays.next(connected).second);
  ASSERT_TRUE(quiet(nh));  // that re-run is through
  const auto burst = overlays.size();
  const auto burst_start = Clock::now();
  for (int i = 0; i < 20; ++i) {
    burst_call.request.value = std::to_string(i % 2 ? 40.0 : -20.0 + i);
    ASSERT_TRUE(client.call(burst_call) && burst_call.response.success) << burst_call.response.message;
  }
  const double burst_s = seconds(Clock::now() - burst_start);
  std::printf("burst of 20 changes: %.1f ms; pipeline %.1f ms\n", burst_s * 1e3, processing * 1e3);
  // (~0.05 s here; slower on a loaded machine: the bound on re-runs below grows with it)
  burst_call.request.value = "30.0";  // the last value
  ASSERT_TRUE(client.call(burst_call) && burst_call.response.success);
  ASSERT_TRUE(overlays.next(burst).second);
  ASSERT_TRUE(quiet(nh));  // any stale re-run would have come by now
  const auto reruns = overlays.since(burst);
  // About one re-run per throttle interval (at least 40 ms) during the burst, and the last one.
  EXPECT_LE(reruns.size(), std::max<std::size_t>(5, 2 + static_cast<std::size_t>(burst_s / 0.04))) << "a queue of stale re-runs";
  for (const auto& r : reruns) EXPECT_EQ(r->header.stamp, stamps[7]);

  // The same value alone gives the same overlay as the burst's last re-run.
  set("threshold", "c", "29.5");
  ASSERT_TRUE(overlays.next(burst + reruns.size()).second);
  const auto other = overlays.size();
  set("threshold", "c", "30.0");
  auto reference = overlays.next(other).second;
  ASSERT_TRUE(reference);
  EXPECT_TRUE(sameImage(*reruns.back(), *reference)) << "the last re-run did not use the last value";
}

TEST(HeldFrame, WhoeverWatchesAPortOfTheHeldGraphGetsTheHeldFrameAtOnce) {
  // "Show in rviz" or a preview on a held graph: the port's topic is new, no frame will pass by
  // itself; each watcher that subscribes gets the held frame (the previous test held frame 7)
  ros::NodeHandle nh;
  const auto stamps = bagStamps();
  ASSERT_TRUE(quiet(nh));
  apex::Inspect::Request req;
  req.node = "threshold", req.port = "image", req.enable = true;
  const auto res = call<apex::Inspect>("inspect", req);
  ASSERT_TRUE(res.success) << res.message;
  for (const char* watcher : {"a display", "a preview after it"}) {
    sensor_msgs::Image image;
    ASSERT_TRUE(receive(nh, res.topic, image)) << watcher << " got nothing on the held graph's " << res.topic;
    EXPECT_EQ(image.header.stamp, stamps[7]) << watcher;
  }
  req.enable = false;
  ASSERT_TRUE(call<apex::Inspect>("inspect", req).success);
  ASSERT_TRUE(quiet(nh));
}

TEST(HeldFrame, AStepIsOneFrameThroughBothThreadGroups) {
  ros::NodeHandle nh;
  Overlays overlays(nh);
  ASSERT_TRUE(overlays.waitConnected()) << "the overlay publisher never connected";
  const auto stamps = bagStamps();
  apex::Control::Request pause, step;
  pause.command = "pause", step.command = "step";
  ASSERT_TRUE(call<apex::Control>("control", pause).success);
  set("bag", "frame", "20");  // asked for; the paused graph holds it
  set("bag", "playing", "true");  // and then the frames after it
  for (int k : {20, 21, 22}) {
    apex::RuntimeStatus before, after;
    ASSERT_TRUE(receive(nh, "/apex/status", before));
    const auto first = overlays.size();
    auto stepped = call<apex::Control>("control", step);
    ASSERT_TRUE(stepped.success) << stepped.message;
    auto image = overlays.next(first).second;
    ASSERT_TRUE(image) << "a step sent no overlay";
    EXPECT_EQ(image->header.stamp, stamps[k]) << "step to frame " << k;
    ASSERT_TRUE(receive(nh, "/apex/status", after));
    std::map<std::string, std::uint64_t> fired;
    for (const auto& n : before.nodes) fired[n.name] = n.firings;
    for (const auto& n : after.nodes) fired[n.name] = n.firings - fired[n.name];
    for (const auto& [name, n] : fired) EXPECT_EQ(n, 1u) << name << " fired " << n << " times in one step";
    EXPECT_EQ(overlays.size(), first + 1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_held_frame");
  if (argc < 2) {
    std::fprintf(stderr, "usage: test_ros_held_frame BAG\n");
    return 2;
  }
  g_bag = argv[1];
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
