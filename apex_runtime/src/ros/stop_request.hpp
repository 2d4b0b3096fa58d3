// The nodelet tools' way to be asked to stop: SIGINT, SIGTERM, or `rosnode kill` (the XML-RPC
// shutdown call), each only noted, so that the tool unloads what it must before it goes.
#pragma once

#include <ros/xmlrpc_manager.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <thread>

namespace apex {
namespace ros_host {

inline std::atomic<bool> g_stop_requested{false};

/** @brief Notes SIGINT and SIGTERM from now on; a second one ends the process at once (an unload
 *  that hangs, in a node stuck in its work, cannot keep it: roslaunch sends SIGTERM after
 *  SIGINT). Call before ros::init with NoSigintHandler. */
inline void noteStopSignals() {
  auto note = [](int) {
    if (g_stop_requested.exchange(true)) std::_Exit(130);
  };
  std::signal(SIGINT, note);
  std::signal(SIGTERM, note);
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
