// Mirrors parameter values on the ROS parameter server under ~nodes/<node>/<param>,
// so `rosparam get` reads them. One way: values set there are not read back.
#pragma once

#include <apex/GraphState.h>
#include <ros/ros.h>

#include <map>
#include <string>

#include "apex/core/graph.hpp"

namespace apex {
namespace ros_host {

class ParamMirror {
 public:
  explicit ParamMirror(ros::NodeHandle private_nh) : nh_(private_nh) {}
  /** @brief Sets what changed since the last call and deletes what is gone. */
  void update(const Graph& graph, const GraphState& state);
  /** @brief The parameter server lost what was set (a new master): the next update sets all. */
  void forget() { last_.clear(); }

 private:
  ros::NodeHandle nh_;
  std::map<std::string, std::string> last_;  // key → value text
};

}  // namespace ros_host
}  // namespace apex
