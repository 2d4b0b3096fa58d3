// GraphModel, new nodes with a link: a node as add_node will make it, which types a link dragged
// to empty canvas may join (by the runtime's own rules), and adding one with its link as one edit.
#include "apex_rviz_plugin/graph_model.hpp"

#include <algorithm>

#include "apex/core/manifest.hpp"  // the events every node has
#include "calls.hpp"

namespace apex_rviz_plugin {
namespace {

using namespace calls;

apex::PortInfo paramPort(const apex::ParamInfo& p, const char* kind) {
  apex::PortInfo port;
  port.name = p.name, port.kind = kind, port.type = p.type, port.description = p.description;
  return port;
}

}  // namespace

bool isBuiltinEvent(const std::string& port) {
  return port == apex::kEnableSlot || port == apex::kDisableSlot || port == apex::kProcessedTrigger;
}

apex::NodeInfo GraphModel::newNode(const apex::NodeTypeInfo& type, const std::string& name) {
  apex::NodeInfo n;  // as the runtime describes an instance (apex_runtime/src/ros/convert.cpp, toNodeInfo)
  n.name = name, n.type = type.id, n.enabled = true, n.state = "ok";
  n.ports = type.ports;
  for (const auto& p : type.parameters) {
    n.parameters.push_back(p);
    n.parameters.back().value = p.default_value;
    if (!p.interactive) continue;
    n.ports.push_back(paramPort(p, "param_in"));
    n.ports.push_back(paramPort(p, "param_out"));
  }
  return n;
}

std::vector<NewLink> GraphModel::linkable(const std::vector<apex::NodeTypeInfo>& types, const std::string& node,
                                          const std::string& port, bool source) const {
  GraphModel probe;  // the graph with the new node in it, and without the link a new one into `port` replaces
  probe.graph_ = graph_;
  probe.has_graph_ = true;
  if (const auto old = source ? std::nullopt : feeding(node, port)) {
    auto& cs = probe.graph_.connections;
    cs.erase(std::remove_if(cs.begin(), cs.end(),
                            [&](const apex::Connection& c) {
                              return c.from_node == old->from_node && c.from_port == old->from_port && c.to_node == node &&
                                     c.to_port == port;
                            }),
             cs.end());
  }
  const std::string name = join(parentOf(node), "new node");  // a space: no node of the graph has this name
  probe.graph_.nodes.emplace_back();
  auto takes = [&](const std::string& p) {
    return (source ? probe.whyNot(node, port, name, p) : probe.whyNot(name, p, node, port)).empty();
  };
  std::vector<NewLink> own, events_only;
  for (const auto& t : types) {
    apex::NodeInfo& added = probe.graph_.nodes.back();
    added = newNode(t, name);
    std::string builtin;  // a port every node has, if it is the only one that fits
    for (const auto& p : added.ports) {
      if (!builtin.empty() && isBuiltinEvent(p.name)) continue;
      if (!takes(p.name)) continue;
      if (!isBuiltinEvent(p.name)) {
        own.push_back({t.id, p.name});
        builtin.clear();
        break;
      }
      builtin = p.name;
    }
    if (!builtin.empty()) events_only.push_back({t.id, builtin});
  }
  own.insert(own.end(), events_only.begin(), events_only.end());
  return own;
}

Edit GraphModel::addLinked(const std::string& type, const std::string& name, double x, double y, const apex::Connection& c) const {
  Edit e = addNode(type, name, x, y);
  const Edit link = connect(c);  // into an input in use: replaces its link, and undo gives it back
  e.label = "Add " + name + (c.from_node == name ? " feeding " + c.to_node + "/" + c.to_port
                                                  : " fed by " + c.from_node + "/" + c.from_port);
  e.apply.insert(e.apply.end(), link.apply.begin(), link.apply.end());
  e.revert.insert(e.revert.begin(), link.revert.begin(), link.revert.end());  // the link first, then the node
  return e;
}

}  // namespace apex_rviz_plugin
