// The service calls the panel's edits are made of, and the path helpers they
// need (private to the model: graph_model.cpp, graph_model_optimise.cpp, clipboard.cpp).
#pragma once

#include <string>

#include "apex_rviz_plugin/graph_model.hpp"

namespace apex_rviz_plugin {
namespace calls {

inline std::string parentOf(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash);
}
inline std::string join(const std::string& parent, const std::string& name) {
  return parent.empty() ? name : parent + "/" + name;
}

/** Whether two connections join the same ports. */
inline bool same(const apex::Connection& a, const apex::Connection& b) {
  return a.from_node == b.from_node && a.from_port == b.from_port && a.to_node == b.to_node && a.to_port == b.to_port;
}

/** UI metadata holding a position. */
inline std::string ui(double x, double y) {
  return "{x: " + std::to_string(static_cast<int>(x)) + ", y: " + std::to_string(static_cast<int>(y)) + "}";
}

inline Call connect(const std::string& service, const apex::Connection& c) {
  apex::Connect::Request r;
  r.from_node = c.from_node, r.from_port = c.from_port, r.to_node = c.to_node, r.to_port = c.to_port;
  return {service, r};
}

inline Call setUi(const std::string& node, const std::string& text) {
  apex::SetUi::Request r;
  r.node = node, r.ui = text;
  return {"set_ui", r};
}

inline Call setParam(const std::string& node, const std::string& param, const std::string& value) {
  apex::SetParameter::Request r;
  r.node = node, r.parameter = param, r.value = value;
  return {"set_parameter", r};
}

inline Call interactive(const std::string& node, const std::string& param, bool on) {
  apex::SetInteractive::Request r;
  r.node = node, r.parameter = param, r.interactive = on;
  return {"set_interactive", r};
}

inline Call enabled(const std::string& node, bool on) {
  apex::SetEnabled::Request r;
  r.node = node, r.enabled = on;
  return {"set_enabled", r};
}

inline Call remove(const std::string& node) {
  apex::RemoveNode::Request r;
  r.name = node;
  return {"remove_node", r};
}

}  // namespace calls
}  // namespace apex_rviz_plugin
