// Interfaces per instance (Manifest::shapedBy): a node's ports follow its
// parameters. A new interface is applied as one edit: ports that keep their
// name and kind keep their connections and messages (a retyped port keeps the
// connections its new type still fits), the connections of vanished ports are
// removed, and liveness, flush and readiness follow through Restructure as for
// any other edit.
#include <algorithm>

#include "apex/core/node_names.hpp"
#include "edit_scope.hpp"
#include "graph_impl.hpp"
#include "live.hpp"
#include "node_state.hpp"
#include "names.hpp"

namespace apex {

using detail::Edge;
using detail::EventEdge;
using detail::NodeState;

namespace detail {
namespace {

/** The type an edge carries, as its sender declares it. */
const TypeInfo* carried(const Edge& e) {
  const Manifest& m = e.from->manifest();
  return e.from_param ? m.params[e.from_index].portType() : m.outputs[e.from_index].type;
}

/** The type an edge's receiver takes. */
const TypeInfo* taken(const Edge& e) {
  const Manifest& m = e.to->manifest();
  return e.to_param ? m.params[e.to_index].portType() : m.inputs[e.to_index].type;
}

Status sameBuiltins(const Manifest& type, const Manifest& next) {
  for (int i : {detail::kEnableIndex, detail::kDisableIndex})
    if (next.slots.size() <= std::size_t(i) || next.slots[i].name != type.slots[i].name)
      return Status::error("it removed or moved the built-in slot '" + type.slots[i].name + "'");
  if (next.triggers.empty() || next.triggers[detail::kProcessedIndex].name != type.triggers[detail::kProcessedIndex].name)
    return Status::error("it removed or moved the built-in trigger 'processed'");
  if (next.source_mode != type.source_mode) return Status::error("it changed how the node is scheduled (driven)");
  for (const auto& p : next.params)  // a host checks paths against its file roots by the type's manifest
    if (p.kind == ParamKind::Path && !type.findParam(p.name))
      return Status::error("it added the path parameter '" + p.name + "': path parameters must be in the type's manifest");
  for (const auto& p : type.params) {
    if (!p.shapes_interface) continue;
    const ParamSpec* q = next.findParam(p.name);
    if (!q || q->kind != p.kind || !q->shapes_interface)
      return Status::error("it removed or changed parameter '" + p.name + "', which decides the ports");
  }
  return Status::ok();
}

/** Every connection of `n` that the interface `next` cannot keep. */
struct Dropped {
  std::vector<std::shared_ptr<Edge>> edges;
  std::vector<std::shared_ptr<EventEdge>> events;
  bool inputs_change = false;  // which data inputs exist, or whether they are optional
};

Dropped dropped(NodeState& n, const Manifest& next) {
  const Manifest& m = n.manifest();
  Dropped d;
  for (std::size_t i = 0; i < m.inputs.size(); ++i) {
    const int k = indexOf(next.inputs, m.inputs[i].name);
    if (k < 0 || next.inputs[k].optional != m.inputs[i].optional) d.inputs_change = true;
    const auto& e = n.inputEdge(static_cast<int>(i));
    if (e && (k < 0 || !compatible(carried(*e), next.inputs[k].type))) d.edges.push_back(e);
  }
  for (const auto& in : next.inputs)
    if (!m.findInput(in.name)) d.inputs_change = true;
  for (std::size_t i = 0; i < m.outputs.size(); ++i) {
    const int k = indexOf(next.outputs, m.outputs[i].name);
    for (const auto& e : n.outputEdges(static_cast<int>(i)))
      if (k < 0 || !compatible(next.outputs[k].type, taken(*e))) d.edges.push_back(e);
  }
  for (std::size_t i = 0; i < m.params.size(); ++i) {
    const int k = indexOf(next.params, m.params[i].name);
    const bool kept = k >= 0 && next.params[k].kind == m.params[i].kind;
    const int p = static_cast<int>(i);
    if (n.paramInEdge(p) && !kept) d.edges.push_back(n.paramInEdge(p));
    for (const auto& e : n.paramOutEdges(p))
      if (!kept) d.edges.push_back(e);
  }
  auto add = [&](const std::vector<std::shared_ptr<EventEdge>>& events) {
    d.events.insert(d.events.end(), events.begin(), events.end());
  };
  for (std::size_t i = 0; i < m.triggers.size(); ++i)
    if (indexOf(next.triggers, m.triggers[i].name) < 0) add(n.triggerEdges(static_cast<int>(i)));
  for (std::size_t i = 0; i < m.slots.size(); ++i)
    if (indexOf(next.slots, m.slots[i].name) < 0) add(n.slotEdges(static_cast<int>(i)));
  return d;
}

}  // namespace

void NodeState::setInterface(std::shared_ptr<const Manifest> next_ptr) {
  NodeState& n = *this;
  const Manifest& m = n.manifest();
  const Manifest& next = *next_ptr;

  std::vector<std::unique_ptr<detail::InputState>> inputs;
  for (std::size_t k = 0; k < next.inputs.size(); ++k) {
    const int i = indexOf(m.inputs, next.inputs[k].name);
    inputs.push_back(i >= 0 ? std::move(n.inputs_[i]) : std::make_unique<detail::InputState>());
    if (inputs.back()->edge) inputs.back()->edge->to_index = static_cast<int>(k);
  }
  std::vector<detail::OutputState> outputs(next.outputs.size());
  for (std::size_t k = 0; k < next.outputs.size(); ++k) {
    const int i = indexOf(m.outputs, next.outputs[k].name);
    if (i < 0) continue;
    outputs[k] = std::move(n.outputs_[i]);
    for (auto& e : outputs[k].edges) e->from_index = static_cast<int>(k);
  }
  std::vector<detail::ParamState> params(next.params.size());
  for (std::size_t k = 0; k < next.params.size(); ++k) {
    const ParamSpec& spec = next.params[k];
    const int i = indexOf(m.params, spec.name);
    if (i >= 0 && m.params[i].kind == spec.kind) {
      params[k] = std::move(n.params_[i]);
      if (!spec.validate(params[k].requested)) params[k].requested = spec.default_value;  // a narrower range
      if (params[k].in_edge) params[k].in_edge->to_index = static_cast<int>(k);
      for (auto& e : params[k].out_edges) e->from_index = static_cast<int>(k);
    } else {
      params[k].requested = params[k].active = spec.default_value;
      params[k].interactive = spec.interactive;
    }
  }
  std::vector<std::vector<std::shared_ptr<EventEdge>>> triggers(next.triggers.size()), slots(next.slots.size());
  for (std::size_t k = 0; k < next.triggers.size(); ++k) {
    const int i = indexOf(m.triggers, next.triggers[k].name);
    if (i >= 0) triggers[k] = std::move(n.trigger_edges_[i]);
    for (auto& e : triggers[k]) e->trigger = static_cast<int>(k);
  }
  for (std::size_t k = 0; k < next.slots.size(); ++k) {
    const int i = indexOf(m.slots, next.slots[k].name);
    if (i >= 0) slots[k] = std::move(n.slot_edges_[i]);
    for (auto& e : slots[k]) e->slot = static_cast<int>(k);
  }

  auto lock = n.shared_.lock();  // other nodes' threads read its ports and parameters under it
  n.inputs_ = std::move(inputs);
  n.outputs_ = std::move(outputs);
  n.params_ = std::move(params);
  n.trigger_edges_ = std::move(triggers);
  n.slot_edges_ = std::move(slots);
  n.iface_ = std::move(next_ptr);
  if (n.node_) (void)resolveHandles(*n.node_, n.manifest());  // a handle whose port went throws when used
}

}  // namespace detail

Result<std::shared_ptr<const Manifest>> Graph::Impl::interfaceFor(const NodeState& n, const std::string& param,
                                                                  const ParamValue* value) const {
  const Manifest& type = *n.type()->manifest;
  if (!type.shape) return n.iface();
  ParamValues values = n.requestedParams();
  if (value) values.set(param, *value);
  auto next = std::make_shared<Manifest>(type);
  auto fail = [&](const std::string& why) {
    return Status::error(nodeLabel(n.name(), n.type()->id) + " cannot make its ports" +
                         (value ? " for " + param + " = " + toText(*value) : std::string()) + ": " + why);
  };
  try {
    if (auto st = type.shape(values, *next); !st) return fail(st.message());
  } catch (const std::exception& ex) {
    return fail(ex.what());
  }
  if (auto st = next->check(); !st) return fail(st.message());
  if (auto st = detail::sameBuiltins(type, *next); !st) return fail(st.message());
  return std::shared_ptr<const Manifest>(std::move(next));
}

void Graph::Impl::applyInterface(NodeState* n, std::shared_ptr<const Manifest> next, const std::function<void()>& also) {
  if (next == n->iface()) {
    if (also) also();
    return;
  }
  detail::Dropped d = detail::dropped(*n, *next);
  std::vector<NodeState*> targets;  // nodes whose data inputs change
  if (d.inputs_change) targets.push_back(n);
  for (const auto& e : d.edges)
    if (!e->to_param) targets.push_back(e->to);
  std::vector<NodeState*> others = detail::EditScope::neighbours(n);
  others.push_back(n);
  detail::Restructure change(targets, others, ran_ && !targets.empty());
  for (const auto& e : d.edges) removeEdge(e);
  for (const auto& e : d.events) removeEvent(e);
  n->setInterface(std::move(next));
  if (also) also();  // inside the edit: the node never fires between its new ports and what made them
  bump();
}

}  // namespace apex
