// ~balance (issue #37): measures each node's time per frame and proposes the thread groups that
// make the graph a pipeline filling the cores (apex/core/balance.hpp); applies them on request.
// Owner: RuntimeHost's Impl. A balance waits for frames (seconds): it runs on a queue and a thread
// of its own, so that it holds none of the threads that answer the other services.
#pragma once

#include <ros/callback_queue.h>
#include <ros/node_handle.h>
#include <ros/service_server.h>
#include <ros/spinner.h>

#include <apex/SetThreadGroup.h>

#include <atomic>
#include <functional>
#include <memory>

#include "apex/core/graph.hpp"

namespace apex {
namespace ros_host {

/** @brief Serves ~balance (Balance.srv) for `graph`, one call at a time on a thread of its own
 *  (calls meanwhile wait their turn; the other services answer). With `apply`, each node is moved
 *  with `set_group` (set_thread_group's own handler: the same checks, and ~graph published); if
 *  one move is refused, those made are moved back and the call says which move failed and why.
 *  Destroyed, it ends a balance that waits for frames and joins its thread. */
class BalanceService {
 public:
  using SetGroup = std::function<bool(SetThreadGroup::Request&, SetThreadGroup::Response&)>;
  BalanceService(ros::NodeHandle& pnh, Graph& graph, SetGroup set_group);
  ~BalanceService();
  BalanceService(const BalanceService&) = delete;
  BalanceService& operator=(const BalanceService&) = delete;

 private:
  ros::CallbackQueue queue_;
  std::atomic<bool> stopping_{false};
  ros::ServiceServer server_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
};

}  // namespace ros_host
}  // namespace apex
