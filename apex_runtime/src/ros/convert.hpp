// Core state → ROS messages. No logic beyond the mapping.
#pragma once

#include <apex/GraphState.h>
#include <apex/NodeTypeInfo.h>
#include <apex/RuntimeStatus.h>

#include "apex/core/graph.hpp"

namespace apex {
namespace ros_host {

NodeTypeInfo toTypeInfo(const NodeType& type);
/** The whole graph, with each node's ports, parameters (current values) and state. */
GraphState toGraphState(const Graph& graph, std::uint64_t revision);
NodeInfo toNodeInfo(const NodeDescription& node);
RuntimeStatus toStatus(const Graph& graph);

}  // namespace ros_host
}  // namespace apex
