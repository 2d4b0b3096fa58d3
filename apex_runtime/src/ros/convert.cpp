#include "convert.hpp"

#include <algorithm>
#include <map>

namespace apex {
namespace ros_host {
namespace {

PortInfo port(const std::string& name, const char* kind, const TypeInfo* type, bool optional, const std::string& description) {
  PortInfo p;
  p.name = name;
  p.kind = kind;
  p.type = type ? type->name : "";
  p.optional = optional;
  p.description = description;
  return p;
}

const char* pathMode(PathMode m) {
  switch (m) {
    case PathMode::Read:
      return "read";
    case PathMode::Write:
      return "write";
    case PathMode::Directory:
      return "directory";
    case PathMode::ReadFileOrFolder:
      return "read_file_or_folder";
  }
  return "";
}

ParamInfo param(const ParamSpec& s, const std::string& value, bool interactive) {
  ParamInfo p;
  p.name = s.name;
  p.kind = s.kindName();
  p.type = s.portType()->name;
  p.default_value = toText(s.default_value);
  p.value = value;
  p.min = s.min;
  p.max = s.max;
  p.step = s.step;
  p.options = s.options;
  if (s.kind == ParamKind::Path) p.path_mode = pathMode(s.path_mode);
  p.interactive = interactive;
  p.shapes_ports = s.shapes_interface;
  p.legacy = s.legacy;
  p.description = s.description;
  return p;
}

std::string state(const NodeDescription& n) {
  if (n.placeholder) return "placeholder";
  if (!n.error.empty()) return "error";
  return n.enabled ? "ok" : "disabled";
}

bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

/** data, parameter or event, from the ports' kinds in the two nodes' interfaces */
std::string connectionKind(const std::map<std::string, const Manifest*>& ifaces, const ConnectionDescription& c) {
  auto get = [&](const std::string& node) -> const Manifest* {
    auto it = ifaces.find(node);
    return it == ifaces.end() ? nullptr : it->second;
  };
  const Manifest* from = get(c.from_node);
  const Manifest* to = get(c.to_node);
  if (from && from->findTrigger(c.from_port)) return "event";
  if ((from && from->findParam(c.from_port)) || (to && to->findParam(c.to_port))) return "parameter";
  return "data";
}

/** The ports of a manifest, parameters apart: a type's, or an instance's interface. */
std::vector<PortInfo> ports(const Manifest& m) {
  std::vector<PortInfo> out;
  for (const auto& p : m.inputs) out.push_back(port(p.name, "input", p.type, p.optional, p.description));
  for (const auto& p : m.outputs) out.push_back(port(p.name, "output", p.type, false, p.description));
  for (const auto& e : m.slots) out.push_back(port(e.name, "slot", nullptr, false, e.description));
  for (const auto& e : m.triggers) out.push_back(port(e.name, "trigger", nullptr, false, e.description));
  return out;
}

}  // namespace

NodeTypeInfo toTypeInfo(const NodeType& type) {
  const Manifest& m = *type.manifest;
  NodeTypeInfo t;
  t.id = type.id;
  t.description = m.description;
  t.category = m.category;
  t.keeps = m.keeps;
  t.ports = ports(m);
  for (const auto& s : m.params) t.parameters.push_back(param(s, toText(s.default_value), s.interactive));
  return t;
}

NodeInfo toNodeInfo(const NodeDescription& n) {
  NodeInfo info;
  info.name = n.name;
  info.type = n.type;
  info.thread_group = n.thread_group;
  info.enabled = n.enabled;
  info.state = state(n);
  info.error = n.error;
  info.ui = n.ui;
  if (n.subgraph) info.subgraph = n.source.empty() ? "inline" : n.source;
  if (!n.interface) return info;  // a placeholder: no ports known
  info.ports = ports(*n.interface);
  info.keeps = n.interface->keeps;
  for (const auto& s : n.interface->params) {
    std::string value = toText(s.default_value);
    for (const auto& [name, text] : n.parameters)
      if (name == s.name) value = text;
    const bool interactive = has(n.interactive, s.name);
    info.parameters.push_back(param(s, value, interactive));
    if (!interactive) continue;
    info.ports.push_back(port(s.name, "param_in", s.portType(), false, s.description));
    info.ports.push_back(port(s.name, "param_out", s.portType(), false, s.description));
  }
  return info;
}

namespace {

/** Every level of subgraphs into one list: nodes by their paths, each level's connections
 *  with paths, and each subgraph's exports as connections of kind "export". */
void flatten(const GraphDescription& d, const std::string& prefix, GraphState& g, std::map<std::string, const Manifest*>& ifaces,
             std::vector<ConnectionDescription>& connections) {
  auto path = [&](const std::string& name) { return prefix.empty() ? name : prefix + "/" + name; };
  for (const auto& n : d.nodes) {
    NodeInfo info = toNodeInfo(n);
    info.name = path(n.name);
    g.nodes.push_back(info);
    ifaces[info.name] = n.interface.get();
  }
  for (auto c : d.connections) {
    c.from_node = path(c.from_node);
    c.to_node = path(c.to_node);
    connections.push_back(c);
  }
  for (const auto& n : d.nodes) {
    if (!n.subgraph) continue;
    const std::string self = path(n.name);
    flatten(*n.subgraph, self, g, ifaces, connections);
    for (const auto& e : n.subgraph->exports)
      for (const auto& inner : e.inner) {
        const auto slash = inner.rfind('/');
        Connection link;
        const bool inward = e.kind == ExportDescription::Kind::Input || e.kind == ExportDescription::Kind::Slot ||
                            e.kind == ExportDescription::Kind::Parameter;
        const std::string node = self + "/" + inner.substr(0, slash), port = inner.substr(slash + 1);
        link.from_node = inward ? self : node;
        link.from_port = inward ? e.name : port;
        link.to_node = inward ? node : self;
        link.to_port = inward ? port : e.name;
        link.kind = "export";
        g.connections.push_back(link);
      }
  }
}

}  // namespace

GraphState toGraphState(const Graph& graph, std::uint64_t revision) {
  const GraphDescription d = graph.describe();
  GraphState g;
  g.revision = revision;
  g.paused = graph.paused();
  g.thread_groups.push_back(kDefaultGroup);
  for (const auto& name : d.thread_groups) g.thread_groups.push_back(name);
  std::map<std::string, const Manifest*> ifaces;
  std::vector<ConnectionDescription> connections;
  flatten(d, "", g, ifaces, connections);
  for (const auto& c : connections) {
    Connection msg;
    msg.from_node = c.from_node;
    msg.from_port = c.from_port;
    msg.to_node = c.to_node;
    msg.to_port = c.to_port;
    msg.kind = connectionKind(ifaces, c);
    g.connections.push_back(msg);
  }
  return g;
}

RuntimeStatus toStatus(const Graph& graph) {
  RuntimeStatus s;
  s.stamp = ros::Time::now();
  s.tracing = graph.tracing();
  for (const auto& n : graph.nodeStats()) {
    NodeStatus ns;
    ns.name = n.name;
    ns.state = !n.error.empty() ? "error" : n.enabled ? "ok" : "disabled";
    ns.error = n.error;
    ns.firings = n.firings;
    ns.nothing_firings = n.nothing_firings;
    ns.last_ms = n.last_ns / 1e6;
    ns.mean_ms = n.mean_ns / 1e6;
    ns.max_ms = n.max_ns / 1e6;
    ns.dropped = n.dropped;
    ns.p50_ms = n.p50_ns / 1e6;
    ns.p95_ms = n.p95_ns / 1e6;
    auto ms = [](std::int64_t ns) { return ns < 0 ? -1.0 : ns / 1e6; };
    for (const auto& o : n.outputs) {
      ns.outputs.push_back(o.name);
      ns.sent.push_back(o.sent);
      ns.output_latency_p50_ms.push_back(ms(o.latency_p50_ns));
      ns.output_latency_p95_ms.push_back(ms(o.latency_p95_ns));
      ns.output_latency_max_ms.push_back(ms(o.latency_max_ns));
    }
    ns.latency_ms = ms(n.latency_mean_ns);
    ns.latency_p50_ms = ms(n.latency_p50_ns);
    ns.latency_p95_ms = ms(n.latency_p95_ns);
    ns.latency_max_ms = ms(n.latency_max_ns);
    ns.latency_frames = n.latency_frames;
    ns.waiting_for = n.waiting_for;
    ns.idle_s = n.idle_s;
    s.nodes.push_back(ns);
  }
  for (const auto& g : graph.groupStats()) {
    GroupStatus gs;
    gs.name = g.name;
    gs.load = g.load();
    gs.firings = g.firings;
    gs.wakeups = g.wakeups;
    s.groups.push_back(gs);
  }
  return s;
}

}  // namespace ros_host
}  // namespace apex
