// The demo graph in topic mode. A held camera keeps its frame and runs it again on a
// change downstream. Malformed messages published to it: each puts the
// receiving node in an error state on ~status naming what is wrong, and the next valid
// frame comes out as usual. Before, the image below crashed the runtime (its height x
// step wraps around 32 bits and so matched its small buffer).
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/image_encodings.h>

#include <algorithm>
#include <cstring>

#include <apex/RuntimeStatus.h>
#include <apex/SetParameter.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include "apex_test/ros_client.hpp"

using namespace apex_test;

namespace {

sensor_msgs::Image image(std::uint32_t width, std::uint32_t height, std::uint32_t step, std::size_t bytes) {
  sensor_msgs::Image m;
  m.header.frame_id = "camera";
  m.header.stamp = ros::Time::now();
  m.width = width, m.height = height, m.step = step, m.encoding = sensor_msgs::image_encodings::BGR8;
  m.data.assign(bytes, 128);
  return m;
}

sensor_msgs::PointCloud2 cloud(std::uint32_t points) {
  sensor_msgs::PointCloud2 m;
  m.header.frame_id = "camera";
  m.header.stamp = ros::Time::now();
  m.width = points, m.height = 1, m.point_step = 16, m.row_step = 16 * points, m.is_dense = true;
  for (std::uint32_t i = 0; i < 3; ++i) {
    sensor_msgs::PointField f;
    f.name = std::string(1, char('x' + i)), f.offset = 4 * i, f.datatype = sensor_msgs::PointField::FLOAT32, f.count = 1;
    m.fields.push_back(f);
  }
  m.data.resize(16 * points);
  for (std::uint32_t p = 0; p < points; ++p) {
    const float xyz[3] = {0.01f * (p % 100), 0.01f * (p / 100), 1.0f};
    std::memcpy(&m.data[16 * p], xyz, sizeof xyz);
  }
  return m;
}

/** The error ~status shows for `node` (waits up to a few statuses for one). */
std::string errorOf(ros::NodeHandle& nh, const std::string& node) {
  for (int i = 0; i < 10; ++i) {
    apex::RuntimeStatus status;
    if (!receive(nh, "/apex/status", status, 3.0)) return "(no ~status: the runtime is gone?)";
    for (const auto& n : status.nodes)
      if (n.name == node && !n.error.empty()) return n.error;
  }
  return "";
}

/** A publisher that knows when the graph's subscriber has connected (roscpp tells it). */
template <class Msg>
class Source {
 public:
  Source(ros::NodeHandle& nh, const std::string& topic)
      : pub_(nh.advertise<Msg>(topic, 1, [this](const ros::SingleSubscriberPublisher&) {
          std::lock_guard<std::mutex> l(m_);
          connected_ = true;
          cv_.notify_all();
        })) {}
  /** Publishes once a subscriber is connected (at most 10 s). */
  void publish(const Msg& m) {
    std::unique_lock<std::mutex> l(m_);
    EXPECT_TRUE(cv_.wait_for(l, std::chrono::seconds(10), [&] { return connected_; })) << pub_.getTopic();
    l.unlock();
    pub_.publish(m);
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  bool connected_ = false;
  ros::Publisher pub_;  // last: its callback uses the members above
};

TEST(BadMessages, AMalformedFrameIsANamedErrorAndTheNextFrameFlows) {
  ros::NodeHandle nh;
  Source<sensor_msgs::Image> images(nh, "/camera/image_raw");
  Source<sensor_msgs::PointCloud2> clouds(nh, "/camera/points");
  TopicCounter<sensor_msgs::Image> overlay(nh, "/apex_demo/overlay");
  TopicCounter<sensor_msgs::PointCloud2> points(nh, "/apex_demo/points");
  // Valid frames until both outputs have shown one (or 20 s). No queues: a frame published
  // while another is in flight is dropped, so each waits for its output (at most 0.5 s).
  auto valid = [&] {
    const long seen_images = overlay.count(), seen_points = points.count();
    for (int i = 0; i < 40 && (overlay.count() == seen_images || points.count() == seen_points); ++i) {
      images.publish(image(640, 480, 640 * 3, 640 * 480 * 3));
      clouds.publish(cloud(2000));
      overlay.waitBeyond(seen_images, 1, 0.5);
      points.waitBeyond(seen_points, 1, 0.5);
    }
    return overlay.count() > seen_images && points.count() > seen_points;
  };
  ASSERT_TRUE(valid()) << "no overlay or no cloud from valid frames";

  images.publish(image(21845, 65536, 65537, 65536));  // 65536 x 65537 wraps to 65536 in 32 bits
  EXPECT_NE(errorOf(nh, "camera").find("step x height needs 4295032832"), std::string::npos) << errorOf(nh, "camera");
  auto far = cloud(100);
  far.fields[1].offset = 1u << 30;
  clouds.publish(far);
  EXPECT_NE(errorOf(nh, "lidar").find("field 'y' (offset 1073741824) does not fit"), std::string::npos) << errorOf(nh, "lidar");

  EXPECT_TRUE(valid()) << "the overlay or the clouds stopped after the malformed frames";
}

/** The stamps of the overlays, as they arrive. */
class Stamps {
 public:
  explicit Stamps(ros::NodeHandle& nh)
      : sub_(nh.subscribe<sensor_msgs::Image>("/apex_demo/overlay", 10, [this](const sensor_msgs::Image::ConstPtr& m) {
          std::lock_guard<std::mutex> l(m_);
          got_.push_back(m->header.stamp);
          cv_.notify_all();
        })) {}
  /** Until an overlay of `stamp` arrives (at most `timeout` s). */
  bool waitFor(const ros::Time& stamp, double timeout = 0.5) {
    std::unique_lock<std::mutex> l(m_);
    return cv_.wait_for(l, std::chrono::duration<double>(timeout),
                        [&] { return std::find(got_.begin(), got_.end(), stamp) != got_.end(); });
  }
  /** Until more than `n` overlays have arrived (at most `timeout` s). */
  bool waitBeyond(std::size_t n, double timeout = 5.0) {
    std::unique_lock<std::mutex> l(m_);
    return cv_.wait_for(l, std::chrono::duration<double>(timeout), [&] { return got_.size() > n; });
  }
  std::vector<ros::Time> all() {
    std::lock_guard<std::mutex> l(m_);
    return got_;
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  std::vector<ros::Time> got_;
  ros::Subscriber sub_;
};

void set(const std::string& node, const std::string& param, const std::string& value) {
  apex::SetParameter::Request r;
  r.node = node, r.parameter = param, r.value = value;
  auto res = call<apex::SetParameter>("set_parameter", r);
  ASSERT_TRUE(res.success) << res.message;
}

TEST(TopicMode, AHeldCameraKeepsItsFrameAndRunsItAgainOnAChange) {
  ros::NodeHandle nh;
  Source<sensor_msgs::Image> images(nh, "/camera/image_raw");
  Stamps overlays(nh);
  auto frame = image(640, 480, 640 * 3, 640 * 480 * 3);
  auto shown = [&](const ros::Time& stamp) {  // published until its overlay comes (a busy graph drops frames)
    frame.header.stamp = stamp;
    for (int i = 0; i < 40; ++i) {
      images.publish(frame);
      if (overlays.waitFor(stamp)) return true;
    }
    return false;
  };
  const ros::Time held(100, 0), later(200, 0), live(300, 0);
  ASSERT_TRUE(shown(held));
  set("camera", "hold", "true");
  frame.header.stamp = later;
  for (int i = 0; i < 5; ++i) images.publish(frame);  // ignored while held
  for (const char* c : {"20.0", "25.0"}) {  // the second within the first's run: it comes after it
    const auto before = overlays.all().size();
    set("threshold", "c", c);
    ASSERT_TRUE(overlays.waitBeyond(before)) << "setting threshold/c to " << c << " did not run the held frame again";
    EXPECT_EQ(overlays.all().back(), held);
  }
  for (const auto& t : overlays.all()) EXPECT_NE(t, later) << "a frame that came while held was processed";
  set("camera", "hold", "false");
  EXPECT_TRUE(shown(live)) << "the camera did not go live again";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_bad_messages");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
