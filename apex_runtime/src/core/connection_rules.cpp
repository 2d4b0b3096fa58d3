#include "apex/core/connection_rules.hpp"

#include <algorithm>
#include <set>

#include "apex/core/node_names.hpp"

namespace apex {
namespace {

bool isSource(PortKind k) { return k == PortKind::Output || k == PortKind::ParamOut || k == PortKind::Trigger; }

std::string withArticle(PortKind k) {
  const std::string n = portKindName(k);
  return (n[0] == 'i' || n[0] == 'o' ? "an " : "a ") + n;
}

std::string where(const std::string& name, const NodeView& n) { return nodeLabel(name, n.type); }

/** "a, b" of the ports of `kind`, or "none" */
std::string list(const NodeView& n, PortKind kind) {
  std::string out;
  for (const auto& p : n.ports)
    if (p.kind == kind) out += (out.empty() ? "" : ", ") + p.name;
  return out.empty() ? "none" : out;
}

std::string listParams(const NodeView& n) {
  std::string out;
  for (const auto& p : n.params) out += (out.empty() ? "" : ", ") + p;
  return out.empty() ? "none" : out;
}

}  // namespace

Result<PortView> connectionEnd(const std::string& name, const NodeView& n, const std::string& port, bool source) {
  for (const auto& p : n.ports)
    if (p.name == port && isSource(p.kind) == source) return p;
  if (std::find(n.params.begin(), n.params.end(), port) != n.params.end())
    return Status::error(portLabel("parameter", port, name) + " is not interactive: make it interactive to give it ports");
  for (const auto& p : n.ports)
    if (p.name == port)
      return Status::error("'" + port + "' is " + (source ? "an input" : "an output") + " of " + where(name, n) +
                           ": a connection goes from an output, parameter or trigger to an input, parameter or slot");
  if (source)
    return Status::error(where(name, n) + " has no output, trigger or parameter '" + port +
                         "' (outputs: " + list(n, PortKind::Output) + "; triggers: " + list(n, PortKind::Trigger) +
                         "; parameters: " + listParams(n) + ")");
  return Status::error(where(name, n) + " has no input, slot or parameter '" + port + "' (inputs: " + list(n, PortKind::Input) +
                       "; slots: " + list(n, PortKind::Slot) + "; parameters: " + listParams(n) + ")");
}

namespace {

/** True if data flows from `from` to `goal` (through data inputs only: those wait for data). */
bool reaches(const ConnectionView& view, const std::string& from, const std::string& goal) {
  std::vector<std::string> stack{from};
  std::set<std::string> seen{from};
  while (!stack.empty()) {
    const std::string n = stack.back();
    stack.pop_back();
    if (n == goal) return true;
    for (auto& next : view.dataReceivers(n))
      if (seen.insert(next).second) stack.push_back(next);
  }
  return false;
}

bool fits(const std::string& from, const std::string& to) { return from == to || from == "any" || to == "any"; }

}  // namespace

const char* portKindName(PortKind k) {
  switch (k) {
    case PortKind::Output:
      return "output";
    case PortKind::ParamOut:
    case PortKind::ParamIn:
      return "parameter";
    case PortKind::Trigger:
      return "trigger";
    case PortKind::Input:
      return "input";
    case PortKind::Slot:
      return "slot";
  }
  return "port";
}

bool portKindFromName(const std::string& name, PortKind* kind) {
  static const std::pair<const char*, PortKind> kNames[] = {{"output", PortKind::Output},    {"param_out", PortKind::ParamOut},
                                                            {"trigger", PortKind::Trigger},  {"input", PortKind::Input},
                                                            {"param_in", PortKind::ParamIn}, {"slot", PortKind::Slot}};
  for (const auto& [n, k] : kNames)
    if (name == n) return *kind = k, true;
  return false;
}

std::string connectionLabel(const ConnectionDescription& c) {
  return c.from_node + "/" + c.from_port + " -> " + c.to_node + "/" + c.to_port;
}

Result<ConnectionEnds> checkConnection(const ConnectionView& view, const ConnectionDescription& c) {
  auto fail = [&](const std::string& why) { return Status::error("cannot connect " + connectionLabel(c) + ": " + why); };
  const auto from = view.node(c.from_node);
  const auto to = view.node(c.to_node);
  if (!from) return fail("no node named '" + c.from_node + "'");
  if (!to) return fail("no node named '" + c.to_node + "'");
  if (from->placeholder || to->placeholder) return ConnectionEnds{};  // kept as written until the type loads
  auto src = connectionEnd(c.from_node, *from, c.from_port, true);
  if (!src) return fail(src.message());
  auto dst = connectionEnd(c.to_node, *to, c.to_port, false);
  if (!dst) return fail(dst.message());
  const PortView& s = src.value();
  const PortView& d = dst.value();

  if ((s.kind == PortKind::Trigger) != (d.kind == PortKind::Slot)) {
    return fail(s.kind == PortKind::Trigger
                    ? "a trigger connects only to slots, and '" + c.to_port + "' is " + withArticle(d.kind)
                    : "a slot receives only triggers, and '" + c.from_port + "' is " + withArticle(s.kind));
  }
  if (s.kind == PortKind::Trigger) {
    if (view.hasEvent(c)) return fail("they are already connected");
    return ConnectionEnds{s, d};
  }
  if (!fits(s.type, d.type))
    return fail(std::string("type mismatch: ") + portKindName(s.kind) + " '" + c.from_port + "' carries " + s.type + ", " +
                portKindName(d.kind) + " '" + c.to_port + "' takes " + d.type);
  const std::string feeder = view.feeding(c.to_node, c.to_port);
  if (!feeder.empty())
    return fail(portLabel(portKindName(d.kind), c.to_port, c.to_node) + " is already connected (from " + feeder +
                "); an input has one source: disconnect it first");
  if (d.kind == PortKind::Input && reaches(view, c.to_node, c.from_node))
    return fail("it would close a cycle (" + c.to_node + " already feeds " + c.from_node + "); a data cycle can never fire");
  return ConnectionEnds{s, d};
}

}  // namespace apex
