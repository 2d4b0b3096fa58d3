// GraphModel, new nodes with a link: a node as add_node will make it, which types a link dragged
// to empty canvas may join, or a link may take in its place (by the runtime's own rules), and
// adding one with its links as one edit.
#include "apex_rviz_plugin/graph_model.hpp"

#include <algorithm>
#include <functional>

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

GraphModel GraphModel::probe(const std::string& level, const std::optional<apex::Connection>& gone) const {
  GraphModel p;
  p.graph_ = graph_;
  p.has_graph_ = true;
  auto& cs = p.graph_.connections;
  if (gone) cs.erase(std::remove_if(cs.begin(), cs.end(), [&](const apex::Connection& c) { return same(c, *gone); }), cs.end());
  p.graph_.nodes.emplace_back();
  p.graph_.nodes.back().name = join(level, "new node");  // a space: no node of the graph has this name
  return p;
}

namespace {

/** The port of `added` that `takes` a link: its first own one, else the first of the events every
 *  node has (`*builtin` true then); "" if none. */
std::string portTaking(const apex::NodeInfo& added, const std::function<bool(const std::string&)>& takes, bool* builtin) {
  std::string event;
  for (const auto& p : added.ports) {
    if (!event.empty() && isBuiltinEvent(p.name)) continue;
    if (!takes(p.name)) continue;
    if (!isBuiltinEvent(p.name)) return *builtin = false, p.name;
    event = p.name;
  }
  *builtin = !event.empty();
  return event;
}

/** The offers' types, fewer of their ends on events every node has (the int) first, else in their order. */
template <class T>
std::vector<T> ownFirst(std::vector<std::pair<int, T>> offers) {
  std::stable_sort(offers.begin(), offers.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<T> out;
  for (auto& o : offers) out.push_back(std::move(o.second));
  return out;
}

/** `next` done after `e`, and undone before it. */
void andThen(Edit& e, const Edit& next) {
  e.apply.insert(e.apply.end(), next.apply.begin(), next.apply.end());
  e.revert.insert(e.revert.begin(), next.revert.begin(), next.revert.end());
}

}  // namespace

std::vector<NewLink> GraphModel::linkable(const std::vector<apex::NodeTypeInfo>& types, const std::string& node,
                                          const std::string& port, bool source) const {
  // the graph with the new node in it, and without the link a new one into `port` replaces
  GraphModel probed = probe(parentOf(node), source ? std::nullopt : feeding(node, port));
  apex::NodeInfo& added = probed.graph_.nodes.back();
  const std::string name = added.name;
  auto takes = [&](const std::string& p) {
    return (source ? probed.whyNot(node, port, name, p) : probed.whyNot(name, p, node, port)).empty();
  };
  std::vector<std::pair<int, NewLink>> offers;
  for (const auto& t : types) {
    added = newNode(t, name);
    bool builtin = false;
    const std::string p = portTaking(added, takes, &builtin);
    if (!p.empty()) offers.push_back({builtin, {t.id, p}});
  }
  return ownFirst(std::move(offers));
}

std::vector<NewInsert> GraphModel::insertable(const std::vector<apex::NodeTypeInfo>& types, const apex::Connection& link) const {
  GraphModel probed = probe(parentOf(link.from_node), link);  // the new node in the link's place
  apex::NodeInfo& added = probed.graph_.nodes.back();
  const std::string name = added.name;
  auto fed = [&](const std::string& p) { return probed.whyNot(link.from_node, link.from_port, name, p).empty(); };
  auto feeds = [&](const std::string& p) { return probed.whyNot(name, p, link.to_node, link.to_port).empty(); };
  std::vector<std::pair<int, NewInsert>> offers;
  for (const auto& t : types) {
    added = newNode(t, name);
    bool in_builtin = false, out_builtin = false;
    const std::string in = portTaking(added, fed, &in_builtin), out = portTaking(added, feeds, &out_builtin);
    if (!in.empty() && !out.empty()) offers.push_back({in_builtin + out_builtin, {t.id, in, out}});
  }
  return ownFirst(std::move(offers));
}

Edit GraphModel::addLinked(const std::string& type, const std::string& name, double x, double y,
                           const apex::Connection& c) const {
  Edit e = addNode(type, name, x, y);
  andThen(e, connect(c));  // into an input in use: replaces its link, and undo gives it back; the link undone first
  e.label = "Add " + name +
            (c.from_node == name ? " feeding " + c.to_node + "/" + c.to_port : " fed by " + c.from_node + "/" + c.from_port);
  return e;
}

Edit GraphModel::addInserted(const std::string& type, const std::string& name, double x, double y, const apex::Connection& link,
                             const std::string& in, const std::string& out) const {
  apex::Connection into = link, out_of = link;
  into.to_node = out_of.from_node = name;
  into.to_port = in, out_of.from_port = out;
  Edit e = addLinked(type, name, x, y, into);
  const auto replaced = feeding(link.to_node, link.to_port);
  andThen(e, connect(out_of));  // into an input: replaces `link`
  if (!replaced || !same(*replaced, link)) andThen(e, disconnect(link));  // into a slot, which takes many: not replaced
  e.label = "Insert " + name + " into " + link.from_node + "/" + link.from_port + " -> " + link.to_node + "/" + link.to_port;
  return e;
}

}  // namespace apex_rviz_plugin
