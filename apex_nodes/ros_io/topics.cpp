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
    sub_ = subscribeImage(apex::nodeHandle(*this), topic_.get(), 1, [this](const MsgPtr& msg) { received(msg); },
                          transport_.get());
  }
  void send(const MsgPtr& msg) override { image_.publish(fromRos(msg)); }
  apex::Output<Image> image_{this, "image"};
  apex::Param<std::string> topic_{this, "topic"};
  apex::Param<std::string> transport_{this, "transport"};
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
    if (pub_.getNumSubscribers() > 0) pub_.publish(toRos(*image_.get()));
  }

 private:
  void advertise() { pub_ = advertiseImage(apex::nodeHandle(*this), topic_.get(), 1); }
  apex::Input<Image> image_{this, "image"};
  apex::Param<std::string> topic_{this, "topic"};
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
    sub_ = apex::nodeHandle(*this).subscribe<sensor_msgs::PointCloud2>(topic_.get(), 1,
                                                                       [this](const MsgPtr& msg) { received(msg); });
  }
  void send(const MsgPtr& msg) override { cloud_.publish(fromRos(msg)); }
  apex::Output<Cloud> cloud_{this, "cloud"};
  apex::Param<std::string> topic_{this, "topic"};
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
    if (pub_.getNumSubscribers() > 0) pub_.publish(toRos(*cloud_.get()));
  }

 private:
  void advertise() { pub_ = apex::nodeHandle(*this).advertise<sensor_msgs::PointCloud2>(topic_.get(), 1); }
  apex::Input<Cloud> cloud_{this, "cloud"};
  apex::Param<std::string> topic_{this, "topic"};
  ros::Publisher pub_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ImageSubscriber, "apex_nodes/ImageSubscriber");
APEX_REGISTER_NODE(apex_nodes::ImagePublisher, "apex_nodes/ImagePublisher");
APEX_REGISTER_NODE(apex_nodes::PointCloudSubscriber, "apex_nodes/PointCloudSubscriber");
APEX_REGISTER_NODE(apex_nodes::PointCloudPublisher, "apex_nodes/PointCloudPublisher");
