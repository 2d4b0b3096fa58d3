// /diagnostics for the graph, through diagnostic_updater: one status per node and one per thread
// group, once a second. Who owns what: `setGraph()` runs under the host's publish lock and keeps
// what ~graph says of each node (type, group, placeholder); the 1 Hz timer, on a spinner thread,
// reads the graph's statistics and runs the updater. One mutex guards both.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include <apex/GraphState.h>
#include <apex/RuntimeStatus.h>

#include <map>
#include <mutex>
#include <set>
#include <string>

#include "apex/core/graph.hpp"

namespace apex {
namespace ros_host {

class Diagnostics {
 public:
  /** @brief Publishes on /diagnostics (in `nh`'s namespace) once a second while anyone listens
   *  (a status per node is a graph-sized message: nobody listening, none is made); `~expected_rates`
   *  ({node: Hz}) under `pnh` names the rates below which a node is WARN (10% tolerance, as
   *  diagnostic_updater's FrequencyStatus). */
  Diagnostics(ros::NodeHandle nh, ros::NodeHandle pnh, const Graph& graph);
  Diagnostics(const Diagnostics&) = delete;
  Diagnostics& operator=(const Diagnostics&) = delete;

  /** @brief What the newest ~graph says of each node. */
  void setGraph(const GraphState& state);

 private:
  void tick();
  void nodeStatus(const std::string& node, diagnostic_updater::DiagnosticStatusWrapper& out);
  void groupStatus(const std::string& group, diagnostic_updater::DiagnosticStatusWrapper& out);

  const Graph& graph_;
  diagnostic_updater::Updater updater_;
  std::map<std::string, double> expected_;  // node -> Hz
  std::mutex mutex_;
  std::map<std::string, NodeInfo> nodes_;  // from ~graph, parameters left out
  std::map<std::string, NodeStatus> stats_;  // this tick's
  std::map<std::string, GroupStatus> groups_;
  std::map<std::string, double> rates_;  // frames per second over the last tick
  std::map<std::string, std::uint64_t> last_firings_;
  ros::WallTime last_tick_;
  std::set<std::string> tasks_;  // the updater's task names
  ros::WallTimer timer_;
  ros::Publisher listeners_;  // the updater's topic, to see whether anyone listens
};

}  // namespace ros_host
}  // namespace apex
