// Setting parameters: by the set_parameter service (through a subgraph's exports), on a node
// being added (before its setup()), and by a node's own request (Node::requestEdit), all through
// setParameterLocked: an interface-shaping one remakes the node's interface as one edit.
#include "apex/core/limits.hpp"
#include "apex/core/node_names.hpp"
#include "graph_impl.hpp"
#include "node_state.hpp"

namespace apex {

using detail::NodeState;

Result<std::string> Graph::Impl::setParameter(const std::string& outer, const std::string& outer_param, const std::string& text) {
  auto lock = lockEdits();
  auto at = subgraphs_.exportedParam(outer, outer_param);
  if (!at) return at.status();
  const std::string node = at.value().first, param = at.value().second;
  auto n = require(node);
  if (!n) return n.status();
  NodeState& s = *n.value();
  if (s.isPlaceholder())
    return Status::error(nodeLabel(node) + " has the unknown type '" + s.typeId() + "': its parameters are kept unchanged");
  auto value = parseParam(s, param, text);
  if (!value) return value.status();
  if (auto st = setParameterLocked(s, s.findParam(param), value.value()); !st) return st;
  return toText(value.value());
}

Result<ParamValue> Graph::Impl::parseParam(const NodeState& s, const std::string& param, const std::string& text) const {
  const int i = s.findParam(param);
  if (i < 0)
    return Status::error(nodeLabel(s.name(), s.typeId()) + " has no parameter '" + param +
                         "' (parameters: " + s.manifest().listParams() + ")");
  if (text.size() > kMaxYamlString)  // a graph file could not hold it
    return Status::error(nodeLabel(s.name()) + ": parameter '" + param + "': a value of " + std::to_string(text.size()) +
                         " characters, over the limit of " + std::to_string(kMaxYamlString));
  auto value = s.manifest().params[i].parse(text);
  if (!value) return Status::error(nodeLabel(s.name()) + ": " + value.message());
  return value;
}

Status Graph::Impl::presetParams(NodeState& s, const std::vector<std::pair<std::string, std::string>>& params) {
  // Not in the graph yet: no edges, no thread; setup() applies them (NodeState::runSetup).
  for (const auto& [param, text] : params) {
    auto value = parseParam(s, param, text);
    if (!value) return value.status();
    if (s.manifest().params[s.findParam(param)].shapes_interface) {
      auto iface = interfaceFor(s, param, &value.value());
      if (!iface) return iface.status();
      s.setInterface(iface.value());
    }
    s.presetParam(s.findParam(param), value.value());
  }
  return Status::ok();
}

Status Graph::Impl::setParameterLocked(NodeState& s, int index, const ParamValue& value) {
  const ParamSpec& spec = s.manifest().params[index];
  if (spec.shapes_interface) {
    const std::string param = spec.name;  // the spec goes with the old interface
    auto iface = interfaceFor(s, param, &value);
    if (!iface) return iface.status();
    applyInterface(&s, iface.value(), [&] { s.requestParam(s.findParam(param), value); });
  } else {
    s.requestParam(index, value);
  }
  changedDownstreamOf(&s);
  bump();
  return Status::ok();
}

void Graph::Impl::applyRequested(const NodePtr& node, const std::string& param, const ParamValue& value) {
  auto lock = lockEdits();
  const auto it = nodes_.find(node->name());
  if (it == nodes_.end() || it->second != node || node->isPlaceholder()) return;  // removed (or replaced) meanwhile
  const int i = node->findParam(param);
  Status st = i < 0 ? Status::error("has no parameter '" + param + "' (parameters: " + node->manifest().listParams() + ")")
                    : node->manifest().params[i].validate(value);
  if (st) st = setParameterLocked(*node, i, value);
  if (st) return;
  const std::string text = "asked to set '" + param + "': " + st.message();  // reportError names the node
  node->post([text](NodeState& n) { n.reportError(text); });  // its error is its group's to set
}

}  // namespace apex
