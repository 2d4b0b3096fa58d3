// ~balance (issue #37): measures each node's time per frame and proposes the thread groups that
// make the graph a pipeline filling the cores (apex/core/balance.hpp); applies them on request.
// Owner: RuntimeHost's Impl; the callback runs on a spinner thread and may wait for frames.
#pragma once

#include <ros/node_handle.h>
#include <ros/service_server.h>

#include <apex/SetThreadGroup.h>

#include <functional>

#include "apex/core/graph.hpp"

namespace apex {
namespace ros_host {

/** @brief Serves ~balance (Balance.srv) for `graph`. With `apply`, each node is moved with
 *  `set_group` (set_thread_group's own handler: the same checks, and ~graph published); if one
 *  move is refused, those made are moved back and the call says which move failed and why. */
ros::ServiceServer serveBalance(ros::NodeHandle& pnh, Graph& graph,
                                std::function<bool(SetThreadGroup::Request&, SetThreadGroup::Response&)> set_group);

}  // namespace ros_host
}  // namespace apex
