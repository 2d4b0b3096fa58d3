#include "apex/ros/node_handles.hpp"

namespace apex {

namespace {
const RosHost* rosHost(const Node& node) { return dynamic_cast<const RosHost*>(node.host()); }
}  // namespace

ros::NodeHandle nodeHandle(const Node& node) {
  const RosHost* host = rosHost(node);
  return host ? host->nodeHandle() : ros::NodeHandle();
}

ros::NodeHandle privateNodeHandle(const Node& node) {
  const RosHost* host = rosHost(node);
  return host ? ros::NodeHandle(host->privateNodeHandle(), node.name()) : ros::NodeHandle("~/" + node.name());
}

}  // namespace apex
