// Connecting and disconnecting: every rule about what may feed what.
#include <algorithm>
#include <set>

#include "apex/core/connection_rules.hpp"
#include "apex/core/limits.hpp"
#include "edit_scope.hpp"
#include "graph_impl.hpp"
#include "live.hpp"
#include "node_state.hpp"
#include "names.hpp"

namespace apex {

using detail::Edge;
using detail::EditScope;
using detail::EventEdge;
using detail::NodeState;
using detail::Restructure;

namespace {

struct Endpoint {
  PortKind kind;
  int index;
  const TypeInfo* type;  // nullptr for events
};

/** A node as the connection rules see it. */
NodeView viewOf(const NodeState& n) {
  NodeView v;
  v.type = n.typeId();
  v.placeholder = n.isPlaceholder();
  if (v.placeholder) return v;
  const Manifest& m = n.manifest();
  for (const auto& p : m.inputs) v.ports.push_back({p.name, PortKind::Input, p.type->name});
  for (const auto& p : m.outputs) v.ports.push_back({p.name, PortKind::Output, p.type->name});
  for (const auto& e : m.slots) v.ports.push_back({e.name, PortKind::Slot, ""});
  for (const auto& e : m.triggers) v.ports.push_back({e.name, PortKind::Trigger, ""});
  for (std::size_t i = 0; i < m.params.size(); ++i) {
    v.params.push_back(m.params[i].name);
    if (!n.interactive(static_cast<int>(i))) continue;
    v.ports.push_back({m.params[i].name, PortKind::ParamIn, m.params[i].portType()->name});
    v.ports.push_back({m.params[i].name, PortKind::ParamOut, m.params[i].portType()->name});
  }
  return v;
}

/** The live graph for the connection rules. */
class LiveView : public ConnectionView {
 public:
  explicit LiveView(const std::map<std::string, std::shared_ptr<NodeState>>& nodes) : nodes_(nodes) {}
  std::optional<NodeView> node(const std::string& name) const override {
    const NodeState* n = find(name);
    return n ? std::optional<NodeView>(viewOf(*n)) : std::nullopt;
  }
  std::string feeding(const std::string& node, const std::string& port) const override {
    const NodeState* n = find(node);
    if (!n || n->isPlaceholder()) return "";
    const Manifest& m = n->manifest();
    std::shared_ptr<Edge> e;
    if (int i = indexOf(m.inputs, port); i >= 0) e = n->inputEdge(i);
    if (int i = indexOf(m.params, port); i >= 0) e = n->paramInEdge(i);
    return e ? e->from->name() : "";
  }
  bool hasEvent(const ConnectionDescription& c) const override {
    const NodeState* from = find(c.from_node);
    if (!from || from->isPlaceholder()) return false;
    const int t = indexOf(from->manifest().triggers, c.from_port);
    if (t < 0) return false;
    for (const auto& e : from->triggerEdges(t))
      if (e->to->name() == c.to_node && e->to->manifest().slots[e->slot].name == c.to_port) return true;
    return false;
  }
  std::vector<std::string> dataReceivers(const std::string& node) const override {
    std::vector<std::string> out;
    const NodeState* n = find(node);
    if (!n) return out;
    n->forEachDataReceiver([&](const Edge& e) { out.push_back(e.to->name()); });
    return out;
  }

 private:
  const NodeState* find(const std::string& name) const {
    auto it = nodes_.find(name);
    return it == nodes_.end() ? nullptr : it->second.get();
  }
  const std::map<std::string, std::shared_ptr<NodeState>>& nodes_;
};

/** Where a port the rules accepted lives in the node. */
Endpoint locate(const NodeState& n, const PortView& p) {
  const Manifest& m = n.manifest();
  switch (p.kind) {
    case PortKind::Input: {
      const int i = indexOf(m.inputs, p.name);
      return {p.kind, i, m.inputs[i].type};
    }
    case PortKind::Output: {
      const int i = indexOf(m.outputs, p.name);
      return {p.kind, i, m.outputs[i].type};
    }
    case PortKind::Slot:
      return {p.kind, indexOf(m.slots, p.name), nullptr};
    case PortKind::Trigger:
      return {p.kind, indexOf(m.triggers, p.name), nullptr};
    case PortKind::ParamIn:
    case PortKind::ParamOut: {
      const int i = indexOf(m.params, p.name);
      return {p.kind, i, m.params[i].portType()};
    }
  }
  return {p.kind, -1, nullptr};
}

/** The edge feeding `to` at `port`, if it comes from `from`/`from_port`. */
std::shared_ptr<Edge> findEdge(NodeState& from, const Endpoint& src, NodeState& to, const Endpoint& dst) {
  std::shared_ptr<Edge> e = dst.kind == PortKind::Input ? to.inputEdge(dst.index) : to.paramInEdge(dst.index);
  const bool from_param = src.kind == PortKind::ParamOut;
  if (e && e->from == &from && e->from_param == from_param && e->from_index == src.index) return e;
  return nullptr;
}

}  // namespace

Status Graph::connect(const std::string& fn, const std::string& fp, const std::string& tn, const std::string& tp) {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  auto st = impl.connectLocked({fn, fp, tn, tp, 0});
  if (!st) return st;
  if (auto targets = impl.subgraphs_.receivers(tn, tp))  // the part it feeds now gets the held frame
    for (const auto& [node, port] : targets.value())
      if (auto to = impl.find(node)) impl.changedDownstreamOf(to.get());
  impl.bump();
  return st;
}

namespace {
/** "detector/image (detector/blur/image): ..." when an end stands for another. */
std::string through(const ConnectionDescription& asked, const ConnectionDescription& real, const std::string& why) {
  if (asked == real) return why;
  return "(" + connectionLabel(asked) + " stands for " + connectionLabel(real) + ") " + why;
}
}  // namespace

Status Graph::Impl::connectLocked(const ConnectionDescription& c) {
  auto from = subgraphs_.sender(c.from_node, c.from_port);
  if (!from) return Status::error("cannot connect " + connectionLabel(c) + ": " + from.message());
  auto to = subgraphs_.receivers(c.to_node, c.to_port);
  if (!to) return Status::error("cannot connect " + connectionLabel(c) + ": " + to.message());
  std::vector<ConnectionDescription> done;
  for (const auto& [node, port] : to.value()) {
    const ConnectionDescription real{from.value().first, from.value().second, node, port, c.line};
    if (auto st = connectDirect(real); !st) {
      for (const auto& d : done) (void)disconnectDirect(d);
      return Status::error(through(c, real, st.message()));
    }
    done.push_back(real);
  }
  return Status::ok();
}

Status Graph::Impl::connectDirect(const ConnectionDescription& c) {
  auto checked = checkConnection(LiveView(nodes_), c);
  if (!checked) return checked.status();
  if (const std::size_t n = connectionCount(); n >= kMaxGraphConnections)
    return Status::error("cannot connect " + connectionLabel(c) + ": the graph has " + std::to_string(n) +
                         " connections, the limit");
  if (!checked.value().from) {  // a placeholder: keep the connection as written
    if (std::find(dormant_.begin(), dormant_.end(), c) != dormant_.end())
      return Status::error("cannot connect " + connectionLabel(c) + ": they are already connected");
    dormant_.push_back(c);
    return Status::ok();
  }
  auto from = find(c.from_node);
  auto to = find(c.to_node);
  const Endpoint s = locate(*from, *checked.value().from), d = locate(*to, *checked.value().to);
  if (s.kind == PortKind::Trigger) {
    EditScope scope;
    scope.involve(from.get());
    scope.involve(to.get());
    auto e = std::make_shared<EventEdge>();
    e->from = from.get(), e->trigger = s.index, e->to = to.get(), e->slot = d.index;
    e->to_source = to->manifest().inputs.empty();
    NodeState::link(e);
    ++links_;
    return Status::ok();
  }
  Restructure change = restructure(from.get(), to.get(), d.kind == PortKind::Input);
  auto e = std::make_shared<Edge>();
  e->from = from.get();
  e->from_param = s.kind == PortKind::ParamOut;
  e->from_index = s.index;
  e->to = to.get();
  e->to_param = d.kind == PortKind::ParamIn;
  e->to_index = d.index;
  e->read_after_firing = !e->from_param && !e->to_param && from->sendsNewest();
  NodeState::link(e);
  ++links_;
  return Status::ok();
}

Status Graph::disconnect(const std::string& fn, const std::string& fp, const std::string& tn, const std::string& tp) {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  const ConnectionDescription c{fn, fp, tn, tp, 0};
  auto from = impl.subgraphs_.sender(fn, fp);
  if (!from) return Status::error("cannot disconnect " + connectionLabel(c) + ": " + from.message());
  auto to = impl.subgraphs_.receivers(tn, tp);
  if (!to) return Status::error("cannot disconnect " + connectionLabel(c) + ": " + to.message());
  Status result = Status::ok();
  bool any = false;
  for (const auto& [node, port] : to.value()) {
    const ConnectionDescription real{from.value().first, from.value().second, node, port, 0};
    auto st = impl.disconnectDirect(real);
    any = any || st.isOk();
    if (!st && result) result = Status::error(through(c, real, st.message()));
  }
  if (any) impl.bump();
  return any ? Status::ok() : result;
}

Status Graph::Impl::disconnectDirect(const ConnectionDescription& c) {
  const std::string &fn = c.from_node, &fp = c.from_port, &tn = c.to_node, &tp = c.to_port;
  auto fail = [&](const std::string& why) { return Status::error("cannot disconnect " + connectionLabel(c) + ": " + why); };
  auto dormant = std::find(dormant_.begin(), dormant_.end(), c);
  if (dormant != dormant_.end()) {
    dormant_.erase(dormant);
    bump();
    return Status::ok();
  }
  auto from = find(fn);
  auto to = find(tn);
  if (!from) return fail("no node named '" + fn + "'");
  if (!to) return fail("no node named '" + tn + "'");
  auto src_port = connectionEnd(fn, viewOf(*from), fp, true);
  if (!src_port) return fail(src_port.message());
  auto dst_port = connectionEnd(tn, viewOf(*to), tp, false);
  if (!dst_port) return fail(dst_port.message());
  const Endpoint src = locate(*from, src_port.value()), dst = locate(*to, dst_port.value());
  if (src.kind == PortKind::Trigger && dst.kind == PortKind::Slot) {
    for (auto& e : from->triggerEdges(src.index)) {
      if (e->to != to.get() || e->slot != dst.index) continue;
      EditScope scope;
      scope.involve(from.get());
      scope.involve(to.get());
      removeEvent(e);
      bump();
      return Status::ok();
    }
    return fail("they are not connected");
  }
  if (dst.kind == PortKind::Slot || src.kind == PortKind::Trigger) return fail("they are not connected");
  auto e = findEdge(*from, src, *to, dst);
  if (!e) return fail("they are not connected");
  {
    Restructure change = restructure(from.get(), to.get(), dst.kind == PortKind::Input);
    removeEdge(e);
  }
  changedDownstreamOf(to.get());
  bump();
  return Status::ok();
}

Restructure Graph::Impl::restructure(NodeState* from, NodeState* to, bool into_data_input) const {
  if (into_data_input) return Restructure({to}, {from}, ran_);
  return Restructure({}, {from, to}, false);  // a parameter input: no data path changes
}

void Graph::Impl::removeEdge(std::shared_ptr<Edge> e) {
  if (e->dead) return;  // removed already
  e->dead = true;
  --links_;
  NodeState::unlink(e);
}

void Graph::Impl::removeEvent(std::shared_ptr<EventEdge> e) {
  if (NodeState::unlink(e)) --links_;  // removed once
}

namespace detail {

// NodeState's side of a connection: here, beside the only edits that make and remove one.

namespace {
template <class E>
bool erase(std::vector<std::shared_ptr<E>>& v, const std::shared_ptr<E>& e) {
  const auto size = v.size();
  v.erase(std::remove(v.begin(), v.end(), e), v.end());
  return size != v.size();
}
}  // namespace

void NodeState::link(const std::shared_ptr<Edge>& e) {
  NodeState& from = *e->from;
  NodeState& to = *e->to;
  if (e->from_param) {
    from.params_[e->from_index].out_edges.push_back(e);
  } else {
    from.outputs_[e->from_index].edges.push_back(e);
    from.readiness_.receiverConnected();
  }
  if (e->to_param) {
    to.params_[e->to_index].in_edge = e;
  } else {
    to.inputs_[e->to_index]->edge = e;
    to.readiness_.inputConnected();
  }
}

void NodeState::unlink(const std::shared_ptr<Edge>& e) {
  NodeState& from = *e->from;
  NodeState& to = *e->to;
  if (e->from_param) {
    erase(from.params_[e->from_index].out_edges, e);
  } else {
    erase(from.outputs_[e->from_index].edges, e);
    from.readiness_.receiverDisconnected();
  }
  if (e->to_param) {
    to.params_[e->to_index].in_edge.reset();
  } else {
    auto& in = *to.inputs_[e->to_index];
    std::lock_guard<std::mutex> lock(in.m);
    in.msg = Message();  // a pending message is dropped with its connection
    in.full.store(false, std::memory_order_relaxed);
    in.edge.reset();
    to.readiness_.inputDisconnected();
  }
  e->unread.store(false, std::memory_order_release);
}

void NodeState::link(const std::shared_ptr<EventEdge>& e) {
  e->from->trigger_edges_[e->trigger].push_back(e);
  e->to->slot_edges_[e->slot].push_back(e);
}

bool NodeState::unlink(const std::shared_ptr<EventEdge>& e) {
  erase(e->from->trigger_edges_[e->trigger], e);
  return erase(e->to->slot_edges_[e->slot], e);
}

std::vector<std::shared_ptr<Edge>> NodeState::edges() const {
  std::vector<std::shared_ptr<Edge>> out;
  forEachSender([&](const std::shared_ptr<Edge>& e) {
    if (e) out.push_back(e);
  });
  for (const auto& o : outputs_) out.insert(out.end(), o.edges.begin(), o.edges.end());
  for (const auto& p : params_) out.insert(out.end(), p.out_edges.begin(), p.out_edges.end());
  return out;
}

std::vector<std::shared_ptr<EventEdge>> NodeState::events() const {
  std::vector<std::shared_ptr<EventEdge>> out;
  for (const auto& t : trigger_edges_) out.insert(out.end(), t.begin(), t.end());
  for (const auto& s : slot_edges_) out.insert(out.end(), s.begin(), s.end());
  return out;
}

}  // namespace detail

}  // namespace apex
