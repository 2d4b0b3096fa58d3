// The shape of the publisher nodes: one input, a `topic` parameter, advertised at setup and again
// when the topic changes; a message is converted only while someone subscribes.
#pragma once

#include <ros/ros.h>

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
  /** @brief A sink's manifest: its description, the input, and the topic with its default; in "ROS I/O". */
  static apex::Manifest sinkManifest(std::string description, const apex::InputPort<T>& in, std::string topic) {
    return apex::Manifest(std::move(description))
        .inCategory("ROS I/O")
        .input(in)
        .param(apex::param::text("topic").init(std::move(topic)).describe("resolved in the runtime's namespace"));
  }

  void setup() override { pub_ = advertise(apex::nodeHandle(*this), topic_.get()); }
  void parameterChanged(const std::string&) override { setup(); }
  void process() override {
    if (pub_.getNumSubscribers() > 0) pub_.publish(toRos(*in_.get()));
  }

 protected:
  explicit TopicSink(const apex::InputPort<T>& in) : in_(this, in) {}
  /** Advertises `topic` (on the node's thread group). */
  virtual Publisher advertise(ros::NodeHandle nh, const std::string& topic) = 0;

 private:
  apex::Input<T> in_;
  apex::Param<std::string> topic_{this, "topic"};
  Publisher pub_;
};

}  // namespace apex_nodes
