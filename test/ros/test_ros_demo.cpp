// The demo graph fed by rosbag play, or by its own BagReader: every frame is processed, each published
// overlay equals the same OpenCV calls made directly on the bag's frame, and
// each frame's region count matches the ground truth.
#include <apex/Inspect.h>
#include <apex/SetParameter.h>
#include <cv_bridge/cv_bridge.h>
#include <gmock/gmock.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/Int32.h>
#include <std_msgs/String.h>
#include <std_srvs/SetBool.h>
#include <yaml-cpp/yaml.h>

#include <map>
#include <thread>
#include <opencv2/imgproc.hpp>

#include "apex_test/ros_client.hpp"

using namespace apex_test;

namespace {

std::string g_bag, g_truth, g_source = "topic";

/** The pipeline of graphs/paper_pipeline_topics.yaml, written directly with OpenCV. */
cv::Mat expectedOverlay(const cv::Mat& frame, int* regions) {
  cv::Mat upright, gray, binary, closed, labels, stats, centroids;
  cv::rotate(frame, upright, cv::ROTATE_90_COUNTERCLOCKWISE);
  cv::cvtColor(upright, gray, cv::COLOR_BGR2GRAY);
  cv::adaptiveThreshold(gray, binary, 255, cv::ADAPTIVE_THRESH_GAUSSIAN_C, cv::THRESH_BINARY_INV, 101, 25);
  cv::morphologyEx(binary, closed, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(7, 7)));
  const int n = cv::connectedComponentsWithStats(closed, labels, stats, centroids, 8, CV_32S, cv::CCL_DEFAULT);
  cv::Mat overlay = upright.clone();
  *regions = 0;
  for (int i = 1; i < n; ++i) {
    const int area = stats.at<int>(i, cv::CC_STAT_AREA);
    if (area < 1500 || area > 20000) continue;
    ++*regions;
    cv::rectangle(overlay, cv::Rect(stats.at<int>(i, 0), stats.at<int>(i, 1), stats.at<int>(i, 2), stats.at<int>(i, 3)),
                  cv::Scalar(0, 255, 0), 2);
  }
  return overlay;
}

TEST(Demo, EveryFrameProcessedOverlayExactCountsMatchTheGroundTruth) {
  std::vector<int> truth;
  for (const auto& f : YAML::LoadFile(g_truth)["frames"]) truth.push_back(f["signs"].as<int>());
  ASSERT_EQ(truth.size(), 40u);

  std::mutex m;
  std::condition_variable cv;
  std::map<ros::Time, sensor_msgs::ImageConstPtr> overlays;
  std::vector<int> counts;
  ros::NodeHandle nh;
  auto sub = nh.subscribe<sensor_msgs::Image>("/apex_demo/overlay", 100, [&](const sensor_msgs::ImageConstPtr& img) {
    std::lock_guard<std::mutex> l(m);
    overlays[img->header.stamp] = img;
    cv.notify_all();
  });
  apex::Inspect::Request inspect;
  inspect.node = "blobs", inspect.port = "count", inspect.enable = true;
  ASSERT_TRUE(call<apex::Inspect>("inspect", inspect).success);
  inspect.node = "voxels", inspect.port = "cloud";  // clouds are inspected as sensor_msgs/PointCloud2
  auto cloud_topic = call<apex::Inspect>("inspect", inspect);
  ASSERT_TRUE(cloud_topic.success) << cloud_topic.message;
  EXPECT_EQ(cloud_topic.message_type, "sensor_msgs/PointCloud2");
  sensor_msgs::PointCloud2 filtered;
  std::thread cloud_waiter([&] { EXPECT_TRUE(receive(nh, cloud_topic.topic, filtered)) << "no filtered cloud"; });
  // previews of the overlay, as the panel's thumbnails: throttled and scaled down
  inspect.node = "overlay", inspect.port = "image", inspect.preview = true;
  auto preview_topic = call<apex::Inspect>("inspect", inspect);
  ASSERT_TRUE(preview_topic.success) << preview_topic.message;
  EXPECT_EQ(preview_topic.topic, "/apex/preview/overlay/image");
  inspect.preview = false;
  std::vector<std::pair<ros::WallTime, sensor_msgs::ImageConstPtr>> previews;
  auto preview_sub = nh.subscribe<sensor_msgs::Image>(preview_topic.topic, 100, [&](const sensor_msgs::ImageConstPtr& img) {
    std::lock_guard<std::mutex> l(m);
    previews.emplace_back(ros::WallTime::now(), img);
  });
  std::vector<std::string> abouts;  // what each preview was: the image's real size
  auto about_sub = nh.subscribe<std_msgs::String>(preview_topic.topic + "/about", 100, [&](const std_msgs::String::ConstPtr& s) {
    std::lock_guard<std::mutex> l(m);
    abouts.push_back(s->data);
  });
  auto count_sub = nh.subscribe<std_msgs::Int32>("/apex/inspect/blobs/count", 100, [&](const std_msgs::Int32::ConstPtr& c) {
    std::lock_guard<std::mutex> l(m);
    counts.push_back(c->data);
  });
  ASSERT_TRUE(apex_test::waitUntil(
      [&] {  // every connection stands: no frame may pass before
        for (const ros::Subscriber* s : {&sub, &count_sub, &preview_sub, &about_sub})
          if (s->getNumPublishers() == 0) return false;
        return true;
      },
      30))
      << "not connected to every inspected topic";
  if (g_source == "bag") {  // BagReader inside the graph: start it
    apex::SetParameter::Request play;
    play.node = "bag", play.parameter = "playing", play.value = "true";
    ASSERT_TRUE(call<apex::SetParameter>("set_parameter", play).success);
  } else {  // rosbag play, started paused
    std_srvs::SetBool resume;
    resume.request.data = false;
    ASSERT_TRUE(ros::service::waitForService("/player/pause_playback", ros::Duration(30)));
    ASSERT_TRUE(ros::service::call("/player/pause_playback", resume));
  }

  {
    std::unique_lock<std::mutex> l(m);
    ASSERT_TRUE(cv.wait_for(l, std::chrono::seconds(120), [&] { return overlays.size() >= truth.size(); }))
        << "processed " << overlays.size() << " of " << truth.size() << " frames";
  }
  rosbag::Bag bag(g_bag);
  int frame = 0;
  for (const auto& msg : rosbag::View(bag, rosbag::TopicQuery("/camera/image_raw"))) {
    auto image = msg.instantiate<sensor_msgs::Image>();
    int regions = 0;
    const cv::Mat want = expectedOverlay(cv_bridge::toCvShare(image)->image, &regions);
    std::lock_guard<std::mutex> l(m);
    ASSERT_TRUE(overlays.count(image->header.stamp)) << "frame " << frame << " has no overlay";
    const cv::Mat got = cv_bridge::toCvShare(overlays[image->header.stamp])->image;
    ASSERT_EQ(got.size(), want.size());
    EXPECT_EQ(cv::norm(got, want, cv::NORM_INF), 0.0) << "frame " << frame;
    EXPECT_EQ(regions, truth[frame]) << "frame " << frame;
    if (static_cast<std::size_t>(frame) < counts.size()) EXPECT_EQ(counts[frame], truth[frame]) << "frame " << frame;
    ++frame;
  }
  EXPECT_EQ(frame, 40);
  if (g_source == "bag")  // one firing per frame: image and cloud of a frame leave the player together
    for (const char* node : {"bag", "rotate", "overlay", "passthrough"})
      EXPECT_EQ(firingsOf(nh, node), truth.size()) << node << " did not fire once per frame";
  cloud_waiter.join();
  EXPECT_EQ(filtered.header.frame_id, "camera");
  EXPECT_GT(filtered.width * filtered.height, 100u);
  std::lock_guard<std::mutex> l(m);
  EXPECT_EQ(counts.size(), truth.size());
  ASSERT_GE(previews.size(), 2u);  // while 40 overlays went out whole
  const double seconds = (previews.back().first - previews.front().first).toSec();
  // at most ~5 a second (unthrottled: one per overlay, 10 a second); a second of slack for arrival
  // times a loaded test process compresses
  EXPECT_LE(previews.size(), 2 + 5 * (seconds + 1) * 1.2) << previews.size() << " previews in " << seconds << " s";
  for (const auto& [at, img] : previews) {
    EXPECT_EQ(img->width, 160u);  // 640 wide, scaled down, aspect kept
    EXPECT_EQ(img->height, 120u);
  }
  ASSERT_GE(abouts.size(), 2u);
  const auto& whole = *overlays.begin()->second;
  for (const auto& a : abouts)
    EXPECT_EQ(a, std::to_string(whole.width) + "×" + std::to_string(whole.height) + " " + whole.encoding);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_demo");
  if (argc < 3) {
    std::fprintf(stderr, "usage: test_ros_demo BAG TRUTH [topic|bag]\n");
    return 2;
  }
  g_bag = argv[1], g_truth = argv[2];
  if (argc > 3) g_source = argv[3];
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
