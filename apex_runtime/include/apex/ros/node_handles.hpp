// ROS handles for node types that talk to ROS, handed out by the runtime (as a nodelet
// manager hands out getNodeHandle()): topics resolve in the runtime's namespace with its
// remappings (a nodelet's too), so `ns:=robot1` moves every topic of the graph. A node
// never constructs ros::NodeHandle itself:
//   sub_ = apex::nodeHandle(*this).subscribe(param<std::string>("topic"), 1, ...);
#pragma once

#include <ros/node_handle.h>

#include "apex/core/node.hpp"

namespace apex {

/** @brief What the ROS runtime hosts its graph with (Graph::setHost). */
class RosHost : public Host {
 public:
  /** @param nh the runtime's handle (its namespace); @param pnh its private handle (~). */
  RosHost(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(std::move(nh)), pnh_(std::move(pnh)) {}
  const ros::NodeHandle& nodeHandle() const { return nh_; }
  const ros::NodeHandle& privateNodeHandle() const { return pnh_; }

 private:
  ros::NodeHandle nh_, pnh_;
};

/** @brief The runtime's node handle: for the node's topics. Outside a runtime (a test
 *  harness without a host), the process's default namespace. */
ros::NodeHandle nodeHandle(const Node& node);
/** @brief `~<node name>` under the runtime's private namespace: for the node's own
 *  parameters and topics. */
ros::NodeHandle privateNodeHandle(const Node& node);

}  // namespace apex
