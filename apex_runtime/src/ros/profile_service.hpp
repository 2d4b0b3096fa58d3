// ~node_profile (GetNodeProfile.srv): a node's histograms of firing time and latency, for the
// panel's "Latency histogram" window and for scripts.
#pragma once

#include <ros/ros.h>

#include "apex/core/graph.hpp"

namespace apex {
namespace ros_host {

/** @brief Serves ~node_profile for `graph` (Graph::nodeProfile). */
ros::ServiceServer serveProfile(ros::NodeHandle& pnh, const Graph& graph);

}  // namespace ros_host
}  // namespace apex
