// How a node reads tf2: its own buffer, filled from /tf and /tf_static by tf2_ros's listener on the
// runtime's node handle (its namespace and remappings, apex/ros/node_handles.hpp). TfLookup,
// LaserProjector and MergeClouds each own a TfListener; the listener's thread writes the buffer (tf2
// locks it), the node's thread group reads it.
#pragma once

#include <ros/init.h>
#include <ros/time.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <memory>
#include <string>
#include <utility>

#include "apex/core/declare.hpp"
#include "apex/core/node.hpp"
#include "apex/ros/node_handles.hpp"

namespace apex_nodes {

/** @brief The `timeout` of a node that waits for tf2: seconds, 0 to 10, 0.1 unless set. */
inline apex::ParamDecl<double> tfTimeoutParam(std::string description) {
  return apex::param::number("timeout").range(0.0, 10.0).step(0.01).init(0.1).describe(std::move(description));
}

/** @brief "no transform <source> -> <target> at <seconds>": how a node's error names a transform tf2
 *  does not have; the node adds tf2's reason. */
inline std::string noTransform(const std::string& source, const std::string& target, const ros::Time& stamp) {
  return "no transform " + source + " -> " + target + " at " + std::to_string(stamp.toSec());
}

/** @brief A tf2 buffer and the listener that fills it from /tf and /tf_static. */
class TfListener {
 public:
  /** @brief Listens on `node`'s runtime handle. Without ROS (a test harness, no master to subscribe
   *  through) there is no listener and the buffer stays empty: a lookup between two frames fails
   *  as tf2 fails it (a frame into itself is tf2's identity still). */
  explicit TfListener(const apex::Node& node) {
    if (ros::isInitialized()) listener_ = std::make_unique<tf2_ros::TransformListener>(buffer_, apex::nodeHandle(node));
  }
  /** @brief What has arrived so far; tf2's lookups read it (laser_geometry takes it as tf2::BufferCore). */
  tf2_ros::Buffer& buffer() { return buffer_; }
  /** @brief Waits up to `timeout` seconds until tf2 can map `source` into `target` at `stamp`, while
   *  the listener fills the buffer; at once without a listener (nothing would arrive, and tf2 logs
   *  an error for a wait without one). The lookup after it says what is missing. */
  void waitFor(const std::string& target, const std::string& source, const ros::Time& stamp, double timeout) {
    if (listener_) buffer_.canTransform(target, source, stamp, ros::Duration(timeout));
  }

 private:
  tf2_ros::Buffer buffer_;
  std::unique_ptr<tf2_ros::TransformListener> listener_;  // after buffer_, which it fills: destroyed first
};

}  // namespace apex_nodes
