// The critical path to a node: the chain of data links whose frames arrive last, so that it
// sets the node's latency. The panel colours it (a node's menu: "Critical path to here").
#pragma once

#include <apex/Connection.h>
#include <apex/GraphState.h>
#include <apex/NodeStatus.h>

#include <map>
#include <string>
#include <vector>

namespace apex_rviz_plugin {

/** @brief The data links from a source to `target`, source first, along which its frames come
 *  last: at each node, upstream through the input whose sender is slowest to have its frame,
 *  by the senders' latency p50 from their frames' stamps where every one of them has one (live
 *  stamps), else by the largest sum of mean firing times along the sender's own critical path
 *  (a bag at recorded stamps). Empty if `target` has no data inputs or is unknown. */
std::vector<apex::Connection> criticalPath(const apex::GraphState& graph, const std::map<std::string, apex::NodeStatus>& status,
                                           const std::string& target);

/** @brief What the path costs, for the panel's message: "clock → blur → count: 3.10 ms of firing
 *  time (latency p50 12.0 ms)" (the latency where the target has one). */
std::string describeCriticalPath(const std::vector<apex::Connection>& path, const std::map<std::string, apex::NodeStatus>& status,
                                 const std::string& target);

}  // namespace apex_rviz_plugin
