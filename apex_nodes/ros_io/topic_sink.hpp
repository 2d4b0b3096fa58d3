// The shape of the publisher nodes: one input, `topic` and `queue_size` parameters, advertised at
// setup and again when either changes; a message is converted only while someone subscribes.
#pragma once

#include <ros/ros.h>

#include <cstdint>
#include <string>
#include <utility>

#include "apex/core/node.hpp"
#include "apex/core/ports.hpp"
#include "apex/ros/node_handles.hpp"
#include "apex_nodes/ros_convert.hpp"

namespace apex_nodes {

/** `Publisher`: ros::Publisher or image_transport::Publisher (what advertise() returns). */
template <class T, class Publisher>
class TopicSink : public apex::Node {
 public:
  /** @brief A sink's manifest: its description, the input, the topic with its default, the queue; in "ROS I/O". */
  static apex::Manifest sinkManifest(std::string description, const apex::InputPort<T>& in, std::string topic) {
    return apex::Manifest(std::move(description))
        .inCategory("ROS I/O")
        .input(in)
        .param(apex::param::text("topic").init(std::move(topic)).describe("resolved in the runtime's namespace"))
        .param(
            apex::param::integer("queue_size")
                .range(1, 1000)
                .step(1)
                .init(1)
                .describe(
                    "messages kept for each subscriber that reads slower than the graph sends (ROS's queue_size): 1 keeps "
                    "the newest, as camera drivers do; more, and a slow subscriber (rosbag record, a script) gets every frame"));
  }

  void setup() override { pub_ = advertise(apex::nodeHandle(*this), topic_.get(), std::uint32_t(queue_size_.get())); }
  void parameterChanged(const std::string&) override { setup(); }
  void process() override {
    if (pub_.getNumSubscribers() > 0) pub_.publish(toRos(*in_.get()));
  }

 protected:
  explicit TopicSink(const apex::InputPort<T>& in) : in_(this, in) {}
  /** Advertises `topic` (on the node's thread group) with `queue_size`. */
  virtual Publisher advertise(ros::NodeHandle nh, const std::string& topic, std::uint32_t queue_size) = 0;

 private:
  apex::Input<T> in_;
  apex::Param<std::string> topic_{this, "topic"};
  apex::Param<int> queue_size_{this, "queue_size"};  // (by name: a template's static members have no set order at start-up)
  Publisher pub_;
};

}  // namespace apex_nodes
