// ImageSubscriber, ImagePublisher, PointCloudSubscriber, PointCloudPublisher.
// Subscribers keep only the newest message and can hold one (topic_source.hpp).
// Publishers convert only while someone subscribes.
#include <ros/ros.h>

#include "apex/core/registry.hpp"
#include "apex/ros/node_handles.hpp"
#include "apex_nodes/ros_convert.hpp"
#include "shared_image_transport.hpp"
#include "topic_source.hpp"

namespace apex_nodes {

class ImageSubscriber : public TopicSource<sensor_msgs::Image> {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Receives images from a topic (image_transport); keeps only the newest")
        .output<Image>("image")
        .param(apex::param::text("topic", "image").describe("resolved in the runtime's namespace"))
        .param(apex::param::options("transport", {"raw", "compressed", "theora"}, "raw"))
        .param(holdParam())
        .driven();
  }

 private:
  void subscribe() override {
    sub_ = subscribeImage(apex::nodeHandle(*this), param<std::string>("topic"), 1, [this](const MsgPtr& msg) { received(msg); },
                          param<std::string>("transport"));
  }
  void send(const MsgPtr& msg) override { publish<Image>("image", fromRos(msg)); }
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
  void advertise() { pub_ = advertiseImage(apex::nodeHandle(*this), param<std::string>("topic"), 1); }
  image_transport::Publisher pub_;
};

class PointCloudSubscriber : public TopicSource<sensor_msgs::PointCloud2> {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Receives sensor_msgs/PointCloud2 (x, y, z); keeps only the newest")
        .output<Cloud>("cloud")
        .param(apex::param::text("topic", "points"))
        .param(holdParam())
        .driven();
  }

 private:
  void subscribe() override {
    sub_ = apex::nodeHandle(*this).subscribe<sensor_msgs::PointCloud2>(param<std::string>("topic"), 1,
                                                                       [this](const MsgPtr& msg) { received(msg); });
  }
  void send(const MsgPtr& msg) override { publish<Cloud>("cloud", fromRos(msg)); }
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
  void advertise() { pub_ = apex::nodeHandle(*this).advertise<sensor_msgs::PointCloud2>(param<std::string>("topic"), 1); }
  ros::Publisher pub_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ImageSubscriber, "apex_nodes/ImageSubscriber");
APEX_REGISTER_NODE(apex_nodes::ImagePublisher, "apex_nodes/ImagePublisher");
APEX_REGISTER_NODE(apex_nodes::PointCloudSubscriber, "apex_nodes/PointCloudSubscriber");
APEX_REGISTER_NODE(apex_nodes::PointCloudPublisher, "apex_nodes/PointCloudPublisher");
