// ~inspect: publishes one port's messages on ~inspect/<node>/<port> while
// enabled, and previews (throttled, shrunk) on ~preview/<node>/<port>. Costs
// nothing while off (no tap) or while nobody subscribes. Whoever subscribes to a
// held graph's port gets its frame at once (the held frame is sent again).
#pragma once

#include <ros/ros.h>

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "apex/core/graph.hpp"
#include "apex/ros/inspect.hpp"

namespace apex {
namespace ros_host {

class Inspection {
 public:
  explicit Inspection(ros::NodeHandle private_nh) : nh_(private_nh) {}
  /** Previews: at most this many messages a second, images at most this many pixels wide. */
  static constexpr int kPreviewRate = 5;
  static constexpr int kPreviewWidth = 160;
  /** @brief Enables or disables a port's inspection (or its preview); returns (topic, ROS
   *  message type), empty when disabled. */
  Result<std::pair<std::string, std::string>> set(Graph& graph, const std::string& node, const std::string& port, bool enable,
                                                  bool preview = false);
  void forgetNode(const std::string& node);
  void clear();

 private:
  struct Tap;
  /** A subscriber connected to one of `weak`'s topics (a display or a preview, maybe of a held
   *  graph): the tap installed again, which sends a held frame again, if it is still the port's. */
  void watchedAnew(Graph& graph, const std::string& key, const std::string& node, const std::string& port,
                   const std::weak_ptr<Tap>& weak);
  ros::NodeHandle nh_;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<Tap>> taps_;  // "node/port"
};

}  // namespace ros_host
}  // namespace apex
