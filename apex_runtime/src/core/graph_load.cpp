// Describing the graph as plain data, and replacing it all-or-nothing: a
// description is first built into a private staged graph with the ordinary
// edit calls (so it meets every rule, with the same messages), and only then
// adopted by this one.
#include <algorithm>
#include <set>
#include <tuple>

#include "apex/core/node_names.hpp"
#include "edit_scope.hpp"
#include "graph_impl.hpp"
#include "names.hpp"
#include "node_state.hpp"

namespace apex {

using detail::NodeState;
using detail::ThreadGroup;

namespace {

std::string at(int line) { return line > 0 ? "line " + std::to_string(line) + ": " : ""; }

std::string targetName(const detail::Edge& e) {
  const Manifest& m = e.to->manifest();
  return e.to_param ? m.params[e.to_index].name : m.inputs[e.to_index].name;
}

void describeConnections(const NodeState& n, std::vector<ConnectionDescription>& out) {
  const Manifest& m = n.manifest();
  for (std::size_t i = 0; i < m.outputs.size(); ++i)
    for (auto& e : n.outputEdges(static_cast<int>(i)))
      out.push_back({n.name(), m.outputs[i].name, e->to->name(), targetName(*e), 0});
  for (std::size_t i = 0; i < m.params.size(); ++i)
    for (auto& e : n.paramOutEdges(static_cast<int>(i)))
      out.push_back({n.name(), m.params[i].name, e->to->name(), targetName(*e), 0});
  for (std::size_t i = 0; i < m.triggers.size(); ++i)
    for (auto& e : n.triggerEdges(static_cast<int>(i)))
      out.push_back({n.name(), m.triggers[i].name, e->to->name(), e->to->manifest().slots[e->slot].name, 0});
}

}  // namespace

namespace detail {

NodeDescription NodeState::describe() const {
  auto shared = shared_.lock();
  if (!type_) {
    NodeDescription d = placeholder_;
    d.name = name_;
    d.placeholder = true;
    d.thread_group = group_->name();
    d.ui = shared->ui;
    d.error = "unknown node type '" + d.type + "'";
    return d;
  }
  NodeDescription d;
  d.name = name_;
  d.type = type_->id;
  d.interface = iface_;
  for (std::size_t i = 0; i < params_.size(); ++i) {
    d.parameters.emplace_back(manifest().params[i].name, toText(params_[i].requested));
    if (params_[i].interactive) d.interactive.push_back(manifest().params[i].name);
  }
  d.enabled = shared->enabled;
  d.thread_group = group_->name();
  d.ui = shared->ui;
  return d;
}

}  // namespace detail

GraphDescription Graph::describe() const {
  const Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  return impl.describeLocked();
}

Result<NodeDescription> Graph::describeNode(const std::string& name) const {
  const Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  const Impl::NodePtr n = impl.find(name);
  if (!n) return Status::error("no node named '" + name + "'");
  NodeDescription d = n->describe();
  if (n->type()) d.error = n->error();
  return d;
}

GraphSnapshot Graph::Impl::snapshot() const {
  auto lock = lockEdits();
  auto make = [registry = registry_, host = host_] {
    auto g = std::make_unique<Graph>(registry);
    if (host) g->setHost(host);
    return g;
  };
  return {describeLocked(), make};
}

std::vector<ConnectionDescription> Graph::connections() const {
  const Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  std::vector<ConnectionDescription> out;
  for (auto& [seq, n] : impl.order_) describeConnections(*n, out);
  out.insert(out.end(), impl.dormant_.begin(), impl.dormant_.end());
  return out;
}

GraphDescription Graph::Impl::describeLocked() const {
  GraphDescription flat;
  for (auto& [name, g] : groups_)
    if (name != kDefaultGroup) flat.thread_groups.push_back(name);
  // insertion order, subgraphs among the nodes (a grouped one where its first node was); a
  // subgraph grouped inside another from its first node has the same place: outer first, by path
  std::map<std::tuple<std::uint64_t, int, std::string>, NodeDescription> nodes;
  for (auto& [seq, n] : order_) {
    auto& d = nodes[{seq, 1, ""}] = n->describe();
    if (n->type()) d.error = n->error();
  }
  for (auto& [path, sg] : subgraphs_.all()) {
    NodeDescription d;
    d.name = path;
    d.type = kSubgraphType;
    d.source = sg->source;
    d.enabled = sg->enabled;
    d.ui = sg->ui;
    d.interface = facade(*sg);
    for (const auto& spec : d.interface->params) {
      auto at = subgraphs_.exportedParam(path, spec.name);
      auto n = at ? find(at.value().first) : nullptr;
      const int i = n && n->type() ? n->findParam(at.value().second) : -1;
      if (i < 0) continue;
      d.parameters.emplace_back(spec.name, toText(n->requestedParam(i)));
      if (n->interactive(i)) d.interactive.push_back(spec.name);
    }
    auto inner = std::make_shared<GraphDescription>();
    inner->thread_groups = sg->thread_groups;
    inner->exports = sg->exports;
    d.subgraph = inner;
    nodes[{sg->seq, 0, path}] = std::move(d);
  }
  for (auto& [seq, d] : nodes) flat.nodes.push_back(std::move(d));
  for (auto& [seq, n] : order_) describeConnections(*n, flat.connections);
  flat.connections.insert(flat.connections.end(), dormant_.begin(), dormant_.end());
  return subgraphs_.nest(flat);
}

Result<std::string> Graph::Impl::addPlaceholder(const NodeDescription& d) {
  if (auto why = checkNewPath(d.name); !why.empty()) return Status::error(why);
  const std::string group_name = d.thread_group.empty() ? kDefaultGroup : d.thread_group;
  if (auto room = roomFor(group_name, 1); !room) return Status::error(nodeLabel(d.name) + ": " + room.message());
  auto state = std::make_shared<NodeState>(d.name, nullptr, next_seq_++, revisions_);
  state->setPlaceholder(d);
  state->setUi(d.ui);
  state->setEnabled(d.enabled);
  state->moveTo(group(group_name));
  detail::EditScope scope;
  scope.added(state.get());
  order_[state->seq()] = state.get();
  nodes_[d.name] = std::move(state);
  return d.name;
}

Status Graph::Impl::applyNode(const NodeDescription& d, LoadReport& report) {
  auto fail = [&](const std::string& why) { return Status::error(at(d.line) + why); };
  if (!d.thread_group.empty() && !validName(d.thread_group))
    return fail("thread group name '" + d.thread_group + "' " + kNameRule);
  if (d.type == kSubgraphType) {
    auto added = addSubgraph(d);
    return added ? Status::ok() : fail(added.message());
  }
  if (!validTypeId(d.type)) return fail(nodeLabel(d.name) + ": type '" + d.type + "' " + kTypeIdRule);
  if (!registry_.find(d.type)) {
    auto lock = lockEdits();
    auto added = addPlaceholder(d);
    if (!added) return fail(added.message());
    std::string near;
    for (const auto& id : registry_.closest(d.type)) near += (near.empty() ? " (did you mean " : " or ") + id;
    report.warnings.push_back(at(d.line) + nodeLabel(d.name) + " has the unknown type '" + d.type + "'" +
                              (near.empty() ? "" : near + "?)") + ": kept as a placeholder with its settings, it does not run");
    return Status::ok();
  }
  if (d.name.empty()) return fail("a node needs a name");
  if (auto added = addNode(d); !added) return fail(added.message());
  return Status::ok();
}

Result<LoadReport> Graph::load(const GraphDescription& description) {
  Impl& impl = *impl_;
  auto check = impl.lockEdits();  // refuses node code; released: building the staged graph needs no lock
  check.unlock();
  Impl staged(impl.registry_);
  staged.host_ = impl.host_;
  LoadReport report;
  for (const auto& g : description.thread_groups) {
    if (!validName(g)) return Status::error("thread group name '" + g + "' " + kNameRule);
    if (auto room = staged.roomFor(g); !room) return room;
    staged.group(g);
  }
  for (const auto& node : description.nodes)
    if (auto st = staged.applyNode(node, report); !st) return st;
  for (const auto& c : description.connections) {
    auto lock = staged.lockEdits();
    if (auto st = staged.connectLocked(c); !st) return Status::error(at(c.line) + st.message());
  }
  auto lock = impl.lockEdits();
  impl.adoptLocked(staged, description);
  return report;
}

void Graph::Impl::adoptLocked(Impl& staged, const GraphDescription& description) {
  std::vector<ThreadGroup*> paused;
  for (auto& [name, g] : groups_) {
    g->pause();
    paused.push_back(g.get());
  }
  clearLocked();
  // Groups neither listed nor used by a node go away with the old graph.
  std::set<std::string> keep(description.thread_groups.begin(), description.thread_groups.end());
  keep.insert(kDefaultGroup);
  for (auto& [seq, n] : staged.order_) keep.insert(n->group()->name());
  for (auto it = groups_.begin(); it != groups_.end();) {
    if (keep.count(it->first)) {
      ++it;
      continue;
    }
    paused.erase(std::remove(paused.begin(), paused.end(), it->second.get()), paused.end());
    it->second->stop();
    it = groups_.erase(it);
  }
  for (const auto& name : keep) group(name);
  for (auto& [seq, n] : staged.order_) {
    (void)n->clearQueued();  // the staged groups and their counts go away
    n->joinGraph(revisions_, edits_);
    n->moveTo(group(n->group()->name()));  // off the staged group, which goes
  }
  nodes_ = std::move(staged.nodes_);
  order_ = std::move(staged.order_);
  dormant_ = std::move(staged.dormant_);
  links_ = staged.links_;
  subgraphs_ = std::move(staged.subgraphs_);  // with nothing ungrouped: nothing of the old graph to bring back
  name_counters_ = std::move(staged.name_counters_);
  next_seq_ = staged.next_seq_;
  staged.nodes_.clear();
  staged.order_.clear();
  staged.subgraphs_.clear();
  // Staged mail (setup, parameter and enable changes) was never run: post it for every
  // node before any node may fire (a group runs mail before firing), so a node
  // disabled in the file never fires enabled.
  for (auto& [seq, n] : order_)
    if (n->type())
      n->post([](NodeState& x) {
        x.applyEnabled();
        x.runSetup();  // applies the parameters first
      });
  for (auto& [seq, n] : order_)
    if (n->ready()) n->group()->push(n);
  bump();
  for (ThreadGroup* g : paused) g->resume();
}

}  // namespace apex
