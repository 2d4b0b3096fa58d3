// ImageSubscriber, ImagePublisher, PointCloudSubscriber, PointCloudPublisher.
// Subscribers are driven sources that keep only the newest message: a busy
// graph drops frames instead of queueing them. Publishers convert only while
// someone subscribes.
#include <ros/ros.h>

#include <mutex>

#include "apex/ros/node_plugin.hpp"
#include "apex_nodes/ros_convert.hpp"
#include "shared_image_transport.hpp"

namespace apex_nodes {
namespace {

/** The newest message from a callback thread, taken by process(). */
template <class Ptr>
class Latest {
 public:
  void put(const Ptr& msg) {
    std::lock_guard<std::mutex> lock(m_);
    msg_ = msg;
  }
  Ptr take() {
    std::lock_guard<std::mutex> lock(m_);
    Ptr out;
    std::swap(out, msg_);
    return out;
  }

 private:
  std::mutex m_;
  Ptr msg_;
};

}  // namespace

class ImageSubscriber : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Receives images from a topic (image_transport); keeps only the newest")
        .output<Image>("image")
        .param(apex::param::text("topic", "image").describe("resolved in the runtime's namespace"))
        .param(apex::param::options("transport", {"raw", "compressed", "theora"}, "raw"))
        .driven();
  }
  void setup() override { subscribe(); }
  void parameterChanged(const std::string&) override { subscribe(); }
  void process() override {
    if (auto msg = latest_.take()) publish<Image>("image", fromRos(msg));
  }

 private:
  void subscribe() {
    sub_ = subscribeImage(param<std::string>("topic"), 1,
                          [this](const sensor_msgs::ImageConstPtr& msg) {
                            latest_.put(msg);
                            notifyNewData();
                          },
                          param<std::string>("transport"));
  }
  Latest<sensor_msgs::ImageConstPtr> latest_;
  image_transport::Subscriber sub_;
};

class ImagePublisher : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Publishes images on a topic (image_transport)")
        .input<Image>("image")
        .param(apex::param::text("topic", "image_out"));
  }
  void setup() override { advertise(); }
  void parameterChanged(const std::string&) override { advertise(); }
  void process() override {
    if (pub_.getNumSubscribers() > 0) pub_.publish(toRos(*input<Image>("image")));
  }

 private:
  void advertise() { pub_ = advertiseImage(param<std::string>("topic"), 1); }
  image_transport::Publisher pub_;
};

class PointCloudSubscriber : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Receives sensor_msgs/PointCloud2 (x, y, z); keeps only the newest")
        .output<Cloud>("cloud")
        .param(apex::param::text("topic", "points"))
        .driven();
  }
  void setup() override { subscribe(); }
  void parameterChanged(const std::string&) override { subscribe(); }
  void process() override {
    if (auto msg = latest_.take()) publish<Cloud>("cloud", fromRos(msg));
  }

 private:
  void subscribe() {
    ros::NodeHandle nh;
    sub_ = nh.subscribe<sensor_msgs::PointCloud2>(param<std::string>("topic"), 1,
                                                  [this](const sensor_msgs::PointCloud2ConstPtr& msg) {
                                                    latest_.put(msg);
                                                    notifyNewData();
                                                  });
  }
  Latest<sensor_msgs::PointCloud2ConstPtr> latest_;
  ros::Subscriber sub_;
};

class PointCloudPublisher : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Publishes sensor_msgs/PointCloud2")
        .input<Cloud>("cloud")
        .param(apex::param::text("topic", "points_out"));
  }
  void setup() override { advertise(); }
  void parameterChanged(const std::string&) override { advertise(); }
  void process() override {
    if (pub_.getNumSubscribers() > 0) pub_.publish(toRos(*input<Cloud>("cloud")));
  }

 private:
  void advertise() { pub_ = ros::NodeHandle().advertise<sensor_msgs::PointCloud2>(param<std::string>("topic"), 1); }
  ros::Publisher pub_;
};

}  // namespace apex_nodes

APEX_EXPORT_NODE(apex_nodes, ImageSubscriber, apex_nodes::ImageSubscriber);
APEX_EXPORT_NODE(apex_nodes, ImagePublisher, apex_nodes::ImagePublisher);
APEX_EXPORT_NODE(apex_nodes, PointCloudSubscriber, apex_nodes::PointCloudSubscriber);
APEX_EXPORT_NODE(apex_nodes, PointCloudPublisher, apex_nodes::PointCloudPublisher);
