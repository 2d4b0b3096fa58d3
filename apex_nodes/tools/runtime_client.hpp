// What the demo drivers (apex_tune_report, apex_numbers_report) need of the runtime's services,
// used as a user would with rosservice: a refusal or a missing service ends the demo with its
// message (std::runtime_error).
#pragma once

#include <apex/FireSlot.h>
#include <apex/GetGraph.h>
#include <apex/Inspect.h>
#include <apex/SetParameter.h>
#include <ros/ros.h>

#include <stdexcept>
#include <string>

namespace apex_tools {

/** @brief Calls /apex/NAME; throws std::runtime_error with the service's message if it refuses. */
template <class Srv>
typename Srv::Response call(const std::string& name, typename Srv::Request request) {
  const std::string service = "/apex/" + name;
  if (!ros::service::waitForService(service, ros::Duration(30))) throw std::runtime_error(service + " did not appear");
  Srv srv;
  srv.request = request;
  if (!ros::service::call(service, srv)) throw std::runtime_error(service + " failed");
  if (!srv.response.success) throw std::runtime_error(service + ": " + srv.response.message);
  return srv.response;
}

inline void set(const std::string& node, const std::string& param, const std::string& value) {
  apex::SetParameter::Request r;
  r.node = node, r.parameter = param, r.value = value;
  call<apex::SetParameter>("set_parameter", r);
}

inline void fire(const std::string& node, const std::string& slot) {
  apex::FireSlot::Request r;
  r.node = node, r.slot = slot;
  call<apex::FireSlot>("fire_slot", r);
}

/** @brief Turns on ~inspect for an output; the topic its messages come on. */
inline std::string inspect(const std::string& node, const std::string& port) {
  apex::Inspect::Request r;
  r.node = node, r.port = port, r.enable = true;
  return call<apex::Inspect>("inspect", r).topic;
}

inline apex::GraphState graph() { return call<apex::GetGraph>("get_graph", {}).graph; }

inline const apex::NodeInfo& nodeIn(const apex::GraphState& g, const std::string& name) {
  for (const auto& n : g.nodes)
    if (n.name == name) return n;
  throw std::runtime_error("the graph has no node '" + name + "'");
}

inline std::string valueOf(const apex::GraphState& g, const std::string& node, const std::string& param) {
  for (const auto& p : nodeIn(g, node).parameters)
    if (p.name == param) return p.value;
  throw std::runtime_error("node '" + node + "' has no parameter '" + param + "'");
}

}  // namespace apex_tools
