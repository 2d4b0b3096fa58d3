// dynamic_reconfigure for every node of the graph: each node is served under the runtime's
// private namespace by its path (/apex/threshold, /apex/camera_detector/threshold) with the
// protocol's `set_parameters` service and latched `parameter_descriptions` and
// `parameter_updates` topics, built from the node's parameter specs at run time (no .cfg).
//
// Who owns what: `update()` runs under the host's publish lock and alone makes and drops
// servers; a `set_parameters` call runs on a spinner thread and touches only the graph (through
// the host's setter, which publishes the change), never the servers.
#pragma once

#include <ros/ros.h>

#include <apex/GraphState.h>
#include <dynamic_reconfigure/Config.h>

#include <functional>
#include <map>
#include <memory>
#include <string>

#include "apex/core/graph.hpp"

namespace apex {
namespace ros_host {

class Reconfigure {
 public:
  /** Sets one parameter from YAML text as the `set_parameter` service does (paths confined,
   *  the change published); the applied value's text, or why not. */
  using Setter =
      std::function<Result<std::string>(const std::string& node, const std::string& param, const std::string& yaml_text)>;

  /** `limit`: at most this many servers (nodes beyond it are warned of once). */
  Reconfigure(ros::NodeHandle pnh, Graph& graph, Setter set, int limit = kDefaultLimit);
  ~Reconfigure();
  Reconfigure(const Reconfigure&) = delete;
  Reconfigure& operator=(const Reconfigure&) = delete;

  /** @brief Makes a server for each node of `state` with parameters that has none, drops those
   *  of nodes that are gone or have none, and publishes each node's descriptions when its
   *  parameters' declarations changed and its values when they changed. A call makes at most
   *  kMadePerUpdate servers (each is three calls to the master: a big graph's would hold the
   *  services for seconds), and the graph has at most `limit` (its first nodes with parameters;
   *  `set_parameter` sets every node's). */
  void update(const GraphState& state);
  /** @brief Servers are still to be made: update() again, with the same state if it is current. */
  bool pending() const { return pending_; }

  static constexpr int kMadePerUpdate = 16;
  static constexpr int kDefaultLimit = 500;

 private:
  struct Server;
  /** A `set_parameters` call: every value or none (a refused one puts back those set before it and
   *  is thrown, so roscpp answers with its message); `applied` gets all the node's values. */
  bool setParameters(const std::string& node, const dynamic_reconfigure::Config& request, dynamic_reconfigure::Config& applied);

  ros::NodeHandle pnh_;
  Graph& graph_;
  Setter set_;
  std::map<std::string, std::unique_ptr<Server>> servers_;  // by node path
  int limit_;
  bool pending_ = false;
  std::size_t unserved_ = 0;  // nodes with parameters beyond the limit, as last warned
};

}  // namespace ros_host
}  // namespace apex
