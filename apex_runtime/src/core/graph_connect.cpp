// Connecting and disconnecting: every rule about what may feed what.
#include <algorithm>
#include <set>

#include "apex/core/graph.hpp"
#include "edit_scope.hpp"
#include "live.hpp"
#include "node_state.hpp"

namespace apex {

using detail::Edge;
using detail::EditScope;
using detail::EventEdge;
using detail::NodeState;
using detail::Restructure;

namespace {

enum class Kind { Output, ParamOut, Trigger, Input, ParamIn, Slot };

struct Endpoint {
  Kind kind;
  int index;
  const TypeInfo* type;  // nullptr for events
};

/** "an input", "a slot" */
std::string withArticle(Kind k);

const char* kindName(Kind k) {
  switch (k) {
    case Kind::Output: return "output";
    case Kind::ParamOut: case Kind::ParamIn: return "parameter";
    case Kind::Trigger: return "trigger";
    case Kind::Input: return "input";
    case Kind::Slot: return "slot";
  }
  return "port";
}

std::string withArticle(Kind k) {
  const std::string n = kindName(k);
  return (n[0] == 'i' || n[0] == 'o' ? "an " : "a ") + n;
}

template <class T>
int indexOf(const std::vector<T>& items, const std::string& n) {
  for (std::size_t i = 0; i < items.size(); ++i) if (items[i].name == n) return static_cast<int>(i);
  return -1;
}

std::string where(const NodeState& n) { return "node '" + n.name + "' (" + n.typeId() + ")"; }

Status notInteractive(const NodeState& n, const std::string& p) {
  return Status::error("parameter '" + p + "' of node '" + n.name +
                       "' is not interactive: make it interactive to give it ports");
}

Result<Endpoint> source(const NodeState& n, const std::string& port) {
  const Manifest& m = n.manifest();
  if (int i = indexOf(m.outputs, port); i >= 0) return Endpoint{Kind::Output, i, m.outputs[i].type};
  if (int i = indexOf(m.triggers, port); i >= 0) return Endpoint{Kind::Trigger, i, nullptr};
  if (int i = indexOf(m.params, port); i >= 0) {
    if (!n.params[i].interactive) return notInteractive(n, port);
    return Endpoint{Kind::ParamOut, i, m.params[i].portType()};
  }
  if (indexOf(m.inputs, port) >= 0 || indexOf(m.slots, port) >= 0)
    return Status::error("'" + port + "' is an input of " + where(n) +
                         ": a connection goes from an output, parameter or trigger to an input, parameter or slot");
  return Status::error(where(n) + " has no output, trigger or parameter '" + port + "' (outputs: " + m.listOutputs() +
                       "; triggers: " + m.listTriggers() + "; parameters: " + m.listParams() + ")");
}

Result<Endpoint> target(const NodeState& n, const std::string& port) {
  const Manifest& m = n.manifest();
  if (int i = indexOf(m.inputs, port); i >= 0) return Endpoint{Kind::Input, i, m.inputs[i].type};
  if (int i = indexOf(m.slots, port); i >= 0) return Endpoint{Kind::Slot, i, nullptr};
  if (int i = indexOf(m.params, port); i >= 0) {
    if (!n.params[i].interactive) return notInteractive(n, port);
    return Endpoint{Kind::ParamIn, i, m.params[i].portType()};
  }
  if (indexOf(m.outputs, port) >= 0 || indexOf(m.triggers, port) >= 0)
    return Status::error("'" + port + "' is an output of " + where(n) +
                         ": a connection goes from an output, parameter or trigger to an input, parameter or slot");
  return Status::error(where(n) + " has no input, slot or parameter '" + port + "' (inputs: " + m.listInputs() +
                       "; slots: " + m.listSlots() + "; parameters: " + m.listParams() + ")");
}

/** Nodes downstream of `from` through edges into data inputs (those wait for data). */
bool reaches(const NodeState* from, const NodeState* goal) {
  std::vector<const NodeState*> stack{from};
  std::set<const NodeState*> seen{from};
  while (!stack.empty()) {
    const NodeState* n = stack.back();
    stack.pop_back();
    if (n == goal) return true;
    auto visit = [&](const std::shared_ptr<Edge>& e) {
      if (!e->to_param && seen.insert(e->to).second) stack.push_back(e->to);
    };
    for (auto& o : n->outputs) for (auto& e : o.edges) visit(e);
    for (auto& p : n->params) for (auto& e : p.out_edges) visit(e);
  }
  return false;
}

std::string label(const ConnectionDescription& c) {
  return c.from_node + "/" + c.from_port + " -> " + c.to_node + "/" + c.to_port;
}

/** The edge feeding `to` at `port`, if it comes from `from`/`from_port`. */
std::shared_ptr<Edge> findEdge(NodeState& from, const Endpoint& src, NodeState& to, const Endpoint& dst) {
  std::shared_ptr<Edge> e = dst.kind == Kind::Input ? to.inputs[dst.index]->edge : to.params[dst.index].in_edge;
  const bool from_param = src.kind == Kind::ParamOut;
  if (e && e->from == &from && e->from_param == from_param && e->from_index == src.index) return e;
  return nullptr;
}

}  // namespace

Status Graph::connect(const std::string& fn, const std::string& fp, const std::string& tn, const std::string& tp) {
  auto lock = lockEdits();
  auto st = connectLocked({fn, fp, tn, tp, 0});
  if (!st) return st;
  if (auto to = find(tn)) changedDownstreamOf(to.get());  // the part it feeds now gets the held frame
  bump();
  return st;
}

Status Graph::connectLocked(const ConnectionDescription& c) {
  auto fail = [&](const std::string& why) { return Status::error("cannot connect " + label(c) + ": " + why); };
  auto from = find(c.from_node);
  auto to = find(c.to_node);
  if (!from) return fail("no node named '" + c.from_node + "'");
  if (!to) return fail("no node named '" + c.to_node + "'");
  if (!from->type || !to->type) {  // a placeholder: keep the connection as written
    if (std::find(dormant_.begin(), dormant_.end(), c) != dormant_.end()) return fail("they are already connected");
    dormant_.push_back(c);
    return Status::ok();
  }
  auto src = source(*from, c.from_port);
  if (!src) return fail(src.message());
  auto dst = target(*to, c.to_port);
  if (!dst) return fail(dst.message());
  const Endpoint s = src.value(), d = dst.value();

  if ((s.kind == Kind::Trigger) != (d.kind == Kind::Slot)) {
    return fail(s.kind == Kind::Trigger
                    ? "a trigger connects only to slots, and '" + c.to_port + "' is " + withArticle(d.kind)
                    : "a slot receives only triggers, and '" + c.from_port + "' is " + withArticle(s.kind));
  }
  if (s.kind == Kind::Trigger) {
    for (auto& e : from->trigger_edges[s.index])
      if (e->to == to.get() && e->slot == d.index) return fail("they are already connected");
    EditScope scope;
    scope.involve(from.get());
    scope.involve(to.get());
    auto e = std::make_shared<EventEdge>(EventEdge{from.get(), s.index, to.get(), d.index});
    from->trigger_edges[s.index].push_back(e);
    to->slot_edges[d.index].push_back(e);
    return Status::ok();
  }
  if (!compatible(s.type, d.type))
    return fail(std::string("type mismatch: ") + kindName(s.kind) + " '" + c.from_port + "' carries " + s.type->name +
                ", " + kindName(d.kind) + " '" + c.to_port + "' takes " + d.type->name);
  auto existing = d.kind == Kind::Input ? to->inputs[d.index]->edge : to->params[d.index].in_edge;
  if (existing)
    return fail(std::string(kindName(d.kind)) + " '" + c.to_port + "' of node '" + c.to_node +
                "' is already connected (from " + existing->from->name + "); an input has one source: disconnect it first");
  if (d.kind == Kind::Input && reaches(to.get(), from.get()))
    return fail("it would close a cycle (" + c.to_node + " already feeds " + c.from_node +
                "); a data cycle can never fire");

  Restructure change = restructure(from.get(), to.get(), d.kind == Kind::Input);
  auto e = std::make_shared<Edge>();
  e->from = from.get();
  e->from_param = s.kind == Kind::ParamOut;
  e->from_index = s.index;
  e->to = to.get();
  e->to_param = d.kind == Kind::ParamIn;
  e->to_index = d.index;
  if (e->from_param) {
    from->params[s.index].out_edges.push_back(e);
  } else {
    from->outputs[s.index].edges.push_back(e);
    ++from->counted_out;
  }
  if (e->to_param) {
    to->params[d.index].in_edge = e;
  } else {
    to->inputs[d.index]->edge = e;
    ++to->connected_inputs;
  }
  return Status::ok();
}

Status Graph::disconnect(const std::string& fn, const std::string& fp, const std::string& tn, const std::string& tp) {
  auto lock = lockEdits();
  const ConnectionDescription c{fn, fp, tn, tp, 0};
  auto fail = [&](const std::string& why) { return Status::error("cannot disconnect " + label(c) + ": " + why); };
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
  auto src = source(*from, fp);
  if (!src) return fail(src.message());
  auto dst = target(*to, tp);
  if (!dst) return fail(dst.message());
  if (src->kind == Kind::Trigger && dst->kind == Kind::Slot) {
    for (auto& e : from->trigger_edges[src->index]) {
      if (e->to != to.get() || e->slot != dst->index) continue;
      EditScope scope;
      scope.involve(from.get());
      scope.involve(to.get());
      removeEvent(e);
      bump();
      return Status::ok();
    }
    return fail("they are not connected");
  }
  if (dst->kind == Kind::Slot || src->kind == Kind::Trigger) return fail("they are not connected");
  auto e = findEdge(*from, src.value(), *to, dst.value());
  if (!e) return fail("they are not connected");
  {
    Restructure change = restructure(from.get(), to.get(), dst->kind == Kind::Input);
    removeEdge(e);
  }
  changedDownstreamOf(to.get());
  bump();
  return Status::ok();
}

Restructure Graph::restructure(NodeState* from, NodeState* to, bool into_data_input) const {
  if (into_data_input) return Restructure({to}, {from}, ran_);
  return Restructure({}, {from, to}, false);  // a parameter input: no data path changes
}

void Graph::removeEdge(std::shared_ptr<Edge> e) {
  e->dead = true;
  NodeState* from = e->from;
  NodeState* to = e->to;
  auto erase = [&](std::vector<std::shared_ptr<Edge>>& v) { v.erase(std::remove(v.begin(), v.end(), e), v.end()); };
  if (e->from_param) {
    erase(from->params[e->from_index].out_edges);
  } else {
    erase(from->outputs[e->from_index].edges);
    --from->counted_out;
  }
  if (e->to_param) {
    to->params[e->to_index].in_edge.reset();
  } else {
    auto& in = *to->inputs[e->to_index];
    std::lock_guard<std::mutex> lock(in.m);
    in.msg = Message();  // a pending message is dropped with its connection
    in.full.store(false, std::memory_order_relaxed);
    in.edge.reset();
    --to->connected_inputs;
  }
  e->unread.store(false, std::memory_order_release);
}

void Graph::removeEvent(std::shared_ptr<EventEdge> e) {
  auto erase = [&](std::vector<std::shared_ptr<EventEdge>>& v) { v.erase(std::remove(v.begin(), v.end(), e), v.end()); };
  erase(e->from->trigger_edges[e->trigger]);
  erase(e->to->slot_edges[e->slot]);
}

}  // namespace apex
