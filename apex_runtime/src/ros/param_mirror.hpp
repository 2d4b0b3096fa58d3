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
  /** @brief Sets what changed since the last call and deletes what is gone: one call to the
   *  parameter server for each, or for many (a load), one call that sets the whole tree. */
  void update(const Graph& graph, const GraphState& state);
  /** @brief The parameter server lost what was set (a new master): the next update sets all. */
  void forget() { last_.clear(); }

 private:
  /** Sets ~nodes whole in one call; false if the tree cannot be built (then: one by one). */
  bool setAll(const Graph& graph, const GraphState& state);
  static constexpr std::size_t kOneByOne = 16;  // changes set one call each; more: the whole tree
  ros::NodeHandle nh_;
  std::map<std::string, std::string> last_;  // key → value text
};

}  // namespace ros_host
}  // namespace apex
