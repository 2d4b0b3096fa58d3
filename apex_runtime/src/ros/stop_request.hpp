// The nodelet tools' way to be asked to stop: SIGINT, SIGTERM, or `rosnode kill` (the XML-RPC
// shutdown call), each only noted, so that the tool unloads what it must before it goes.
#pragma once

#include <ros/xmlrpc_manager.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <thread>

namespace apex {
namespace ros_host {

inline std::atomic<bool> g_stop_requested{false};

/** @brief Notes SIGINT and SIGTERM from now on; call before ros::init with NoSigintHandler. */
inline void noteStopSignals() {
  std::signal(SIGINT, [](int) { g_stop_requested = true; });
  std::signal(SIGTERM, [](int) { g_stop_requested = true; });
}

/** @brief Notes `rosnode kill` too (roscpp's own handler would shut ROS down at once); after ros::init. */
inline void noteStopCalls() {
  ros::XMLRPCManager::instance()->unbind("shutdown");
  ros::XMLRPCManager::instance()->bind("shutdown", [](XmlRpc::XmlRpcValue&, XmlRpc::XmlRpcValue& result) {
    g_stop_requested = true;
    result = ros::xmlrpc::responseInt(1, "", 0);
  });
}

/** @brief A short wait between checks (50 ms). */
inline void nap() { std::this_thread::sleep_for(std::chrono::milliseconds(50)); }

}  // namespace ros_host
}  // namespace apex
