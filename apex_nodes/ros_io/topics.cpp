// ImageSubscriber, ImagePublisher, PointCloudSubscriber, PointCloudPublisher.
// Subscribers keep only the newest message and can hold one (topic_source.hpp).
// Publishers convert only while someone subscribes.
#include <ros/ros.h>

#include "apex/core/registry.hpp"
#include "apex/ros/node_handles.hpp"
#include "apex_nodes/ros_convert.hpp"
#include "shared_image_transport.hpp"
#include "topic_sink.hpp"
#include "topic_source.hpp"

namespace apex_nodes {

class ImageSubscriber : public TopicSource<sensor_msgs::Image> {
 public:
  static inline const apex::OutputPort<Image> kImage{"image"};
  static inline const apex::ParamDecl<std::string> kTopic =
      apex::param::text("topic").init("image").describe("resolved in the runtime's namespace");
  static inline const apex::ParamDecl<std::string> kTransport = transportParam();
  static apex::Manifest manifest() {
    return apex::Manifest("Receives images from a topic (image_transport); keeps only the newest")
        .inCategory("ROS I/O")
        .output(kImage)
        .param(kTopic)
        .param(kTransport)
        .param(holdParam())
        .keepsNewest();
  }

 private:
  void subscribe() override {
    sub_ = subscribeImage(
        apex::nodeHandle(*this), topic_.get(), kQueue, [this](const MsgPtr& msg) { received(msg); }, transport_.get());
  }
  void send(const MsgPtr& msg) override { image_.publish(fromRos(msg)); }
  apex::Output<Image> image_{this, kImage};
  apex::Param<std::string> topic_{this, kTopic};
  apex::Param<std::string> transport_{this, kTransport};
  image_transport::Subscriber sub_;
};

class ImagePublisher : public TopicSink<Image, image_transport::Publisher> {
 public:
  static inline const apex::InputPort<Image> kImage{"image", "the frame"};
  static apex::Manifest manifest() { return sinkManifest("Publishes images on a topic (image_transport)", kImage, "image_out"); }
  ImagePublisher() : TopicSink(kImage) {}

 private:
  image_transport::Publisher advertise(ros::NodeHandle nh, const std::string& topic, std::uint32_t queue_size) override {
    return advertiseImage(nh, topic, queue_size);
  }
};

class PointCloudSubscriber : public TopicSource<Cloud> {
 public:
  static inline const apex::OutputPort<Cloud> kCloud{"cloud"};
  static inline const apex::ParamDecl<std::string> kTopic = apex::param::text("topic").init("points");
  static apex::Manifest manifest() {
    return apex::Manifest("Receives sensor_msgs/PointCloud2 with every field (x, y, z and the rest); keeps only the newest")
        .inCategory("ROS I/O")
        .output(kCloud)
        .param(kTopic)
        .param(holdParam())
        .keepsNewest();
  }

 private:
  void subscribe() override {
    sub_ = apex::nodeHandle(*this).subscribe<Cloud>(topic_.get(), kQueue, [this](const MsgPtr& msg) { received(msg); });
  }
  void send(const MsgPtr& msg) override { cloud_.publish(fromRos(msg)); }
  apex::Output<Cloud> cloud_{this, kCloud};
  apex::Param<std::string> topic_{this, kTopic};
  ros::Subscriber sub_;
};

class PointCloudPublisher : public TopicSink<Cloud, ros::Publisher> {
 public:
  static inline const apex::InputPort<Cloud> kCloud{"cloud", "the cloud"};
  static apex::Manifest manifest() {
    return sinkManifest("Publishes sensor_msgs/PointCloud2 with every field the cloud has", kCloud, "points_out");
  }
  PointCloudPublisher() : TopicSink(kCloud) {}

 private:
  ros::Publisher advertise(ros::NodeHandle nh, const std::string& topic, std::uint32_t queue_size) override {
    return nh.advertise<Cloud>(topic, queue_size);
  }
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ImageSubscriber, "apex_nodes/ImageSubscriber");
APEX_REGISTER_NODE(apex_nodes::ImagePublisher, "apex_nodes/ImagePublisher");
APEX_REGISTER_NODE(apex_nodes::PointCloudSubscriber, "apex_nodes/PointCloudSubscriber");
APEX_REGISTER_NODE(apex_nodes::PointCloudPublisher, "apex_nodes/PointCloudPublisher");
