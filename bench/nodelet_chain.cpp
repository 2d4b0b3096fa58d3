// The demo pipeline as a chain of minimal nodelets in one manager: the
// ROS-native baseline for bench/pipeline_bench.cpp. Each stage receives a
// sensor_msgs/Image (shared within the manager: no serialisation), wraps it
// with cv_bridge::toCvShare, runs its OpenCV call, and publishes a new
// message (cv_bridge copies the pixels once). Latency mode: the source sends
// frame i+1 when the sink has acknowledged frame i. Only for benchmarks.
#include <ros/ros.h>
// (ros.h first: nodelet.h needs it)
#include <cv_bridge/cv_bridge.h>
#include <geometry_msgs/PolygonStamped.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/Image.h>
#include <std_msgs/Header.h>

#include <fstream>
#include <map>
#include <mutex>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

namespace apex_bench {

/** One image in, one image out. */
class Stage : public nodelet::Nodelet {
 protected:
  virtual cv::Mat run(const cv::Mat& in, std::string& encoding) = 0;
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    pub_ = nh.advertise<sensor_msgs::Image>(getPrivateNodeHandle().param<std::string>("out", "out"), 1);
    sub_ = nh.subscribe<sensor_msgs::Image>(getPrivateNodeHandle().param<std::string>("in", "in"), 1, &Stage::callback, this);
  }
  void callback(const sensor_msgs::ImageConstPtr& msg) {
    std::string encoding = msg->encoding;
    cv::Mat out = run(cv_bridge::toCvShare(msg)->image, encoding);
    pub_.publish(cv_bridge::CvImage(msg->header, encoding, out).toImageMsg());
  }
  ros::Publisher pub_;
  ros::Subscriber sub_;
};

class Rotate : public Stage {
  cv::Mat run(const cv::Mat& in, std::string&) override {
    cv::Mat out;
    cv::warpAffine(in, out, cv::getRotationMatrix2D(cv::Point2f(in.cols / 2.f, in.rows / 2.f), 15.0, 1.0), in.size());
    return out;
  }
};
class Gray : public Stage {
  cv::Mat run(const cv::Mat& in, std::string& e) override {
    cv::Mat out;
    cv::cvtColor(in, out, cv::COLOR_BGR2GRAY);
    e = "mono8";
    return out;
  }
};
class Threshold : public Stage {
  cv::Mat run(const cv::Mat& in, std::string&) override {
    cv::Mat out;
    cv::adaptiveThreshold(in, out, 255, cv::ADAPTIVE_THRESH_MEAN_C, cv::THRESH_BINARY_INV, 11, 2);
    return out;
  }
};
class Morphology : public Stage {
  cv::Mat run(const cv::Mat& in, std::string&) override {
    cv::Mat out;
    cv::morphologyEx(in, out, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3)));
    return out;
  }
};

/** Connected components; the boxes go out as a polygon (two corners each) with the frame's header. */
class Blobs : public nodelet::Nodelet {
  void onInit() override {
    pub_ = getNodeHandle().advertise<geometry_msgs::PolygonStamped>("regions", 1);
    sub_ = getNodeHandle().subscribe<sensor_msgs::Image>("opened", 1, &Blobs::callback, this);
  }
  void callback(const sensor_msgs::ImageConstPtr& msg) {
    cv::Mat labels, stats, centroids;
    const int n =
        cv::connectedComponentsWithStats(cv_bridge::toCvShare(msg)->image, labels, stats, centroids, 8, CV_32S, cv::CCL_DEFAULT);
    auto out = boost::make_shared<geometry_msgs::PolygonStamped>();
    out->header = msg->header;
    for (int i = 1; i < n; ++i) {
      if (stats.at<int>(i, cv::CC_STAT_AREA) < 50) continue;
      geometry_msgs::Point32 a, b;
      a.x = stats.at<int>(i, 0), a.y = stats.at<int>(i, 1);
      b.x = a.x + stats.at<int>(i, 2), b.y = a.y + stats.at<int>(i, 3);
      out->polygon.points.push_back(a);
      out->polygon.points.push_back(b);
    }
    pub_.publish(out);
  }
  ros::Publisher pub_;
  ros::Subscriber sub_;
};

/** Draws the boxes over the rotated frame of the same sequence number. */
class Overlay : public nodelet::Nodelet {
  void onInit() override {
    pub_ = getNodeHandle().advertise<sensor_msgs::Image>("overlay", 1);
    images_ = getNodeHandle().subscribe<sensor_msgs::Image>("rotated", 2, &Overlay::image, this);
    regions_ = getNodeHandle().subscribe<geometry_msgs::PolygonStamped>("regions", 2, &Overlay::regions, this);
  }
  void image(const sensor_msgs::ImageConstPtr& msg) {
    std::lock_guard<std::mutex> l(m_);
    frames_[msg->header.seq] = msg;
    while (frames_.size() > 4) frames_.erase(frames_.begin());
  }
  void regions(const geometry_msgs::PolygonStampedConstPtr& r) {
    sensor_msgs::ImageConstPtr frame;
    {
      std::lock_guard<std::mutex> l(m_);
      auto it = frames_.find(r->header.seq);
      if (it == frames_.end()) return;
      frame = it->second;
    }
    cv::Mat out = cv_bridge::toCvShare(frame)->image.clone();
    for (std::size_t i = 0; i + 1 < r->polygon.points.size(); i += 2)
      cv::rectangle(out, cv::Point(r->polygon.points[i].x, r->polygon.points[i].y),
                    cv::Point(r->polygon.points[i + 1].x, r->polygon.points[i + 1].y), cv::Scalar(0, 255, 0), 2);
    pub_.publish(cv_bridge::CvImage(frame->header, frame->encoding, out).toImageMsg());
  }
  std::mutex m_;
  std::map<std::uint32_t, sensor_msgs::ImageConstPtr> frames_;
  ros::Publisher pub_;
  ros::Subscriber images_, regions_;
};

/** Sends frames one at a time and measures each from sending to the overlay's arrival. */
class Driver : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    frames_ = pnh.param("frames", 300);
    result_ = pnh.param<std::string>("result", "/tmp/apex_nodelet_chain.txt");
    cv::setNumThreads(pnh.param("opencv_threads", 1));
    cv::RNG rng(7);
    for (int i = 0; i < 8; ++i) {  // the same frames as bench/pipeline_bench.cpp
      cv::Mat m(480, 640, CV_8UC3);
      rng.fill(m, cv::RNG::UNIFORM, 150, 220);
      for (int k = 0; k < 4; ++k)
        cv::rectangle(m, cv::Rect(rng.uniform(20, 520), rng.uniform(20, 360), 80, 80), cv::Scalar::all(30), cv::FILLED);
      images_.push_back(m);
    }
    pub_ = getNodeHandle().advertise<sensor_msgs::Image>("frames", 1);
    sub_ = getNodeHandle().subscribe<sensor_msgs::Image>("overlay", 1, &Driver::arrived, this);
    timer_ = getNodeHandle().createWallTimer(
        ros::WallDuration(1.0),
        [this](const ros::WallTimerEvent&) {
          if (sent_ == 0) send();  // the chain is connected by now
        },
        true);
  }
  void send() {
    std_msgs::Header h;
    h.seq = sent_++;
    start_ = ros::WallTime::now();
    pub_.publish(cv_bridge::CvImage(h, "bgr8", images_[h.seq % images_.size()]).toImageMsg());
  }
  void arrived(const sensor_msgs::ImageConstPtr&) {
    const double ms = (ros::WallTime::now() - start_).toSec() * 1000;
    if (sent_ > 5) total_ += ms, ++counted_;
    if (sent_ < static_cast<unsigned>(frames_)) return send();
    std::ofstream(result_) << total_ / counted_ << "\n";
    ros::shutdown();
  }
  std::vector<cv::Mat> images_;
  int frames_ = 300;
  unsigned sent_ = 0, counted_ = 0;
  double total_ = 0;
  std::string result_;
  ros::WallTime start_;
  ros::Publisher pub_;
  ros::Subscriber sub_;
  ros::WallTimer timer_;
};

}  // namespace apex_bench

PLUGINLIB_EXPORT_CLASS(apex_bench::Rotate, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(apex_bench::Gray, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(apex_bench::Threshold, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(apex_bench::Morphology, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(apex_bench::Blobs, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(apex_bench::Overlay, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(apex_bench::Driver, nodelet::Nodelet)
