// The ROS host: one graph in one process, driven by services. A thin adapter:
// each service converts its request, calls the core Graph, converts the result.
// Used by the standalone node (apex_runtime_node) and the nodelet (apex/Runtime).
#pragma once

#include <ros/ros.h>

#include <memory>

namespace apex {
namespace ros_host {

class RuntimeHost {
 public:
  /** @brief Loads node types through pluginlib, advertises the API under `private_nh`,
   *  loads ~graph if set, starts the graph. */
  RuntimeHost(ros::NodeHandle nh, ros::NodeHandle private_nh);
  /** @brief Stops every thread group. */
  ~RuntimeHost();
  RuntimeHost(const RuntimeHost&) = delete;
  RuntimeHost& operator=(const RuntimeHost&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ros_host
}  // namespace apex
