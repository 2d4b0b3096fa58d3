// Graph::Impl (graph_impl.hpp): lifecycle, node edits and reading. Connections:
// graph_connect.cpp; describing and loading: graph_load.cpp; running and stepping:
// graph_run.cpp; subgraphs: graph_subgraph.cpp.
#include "apex/core/limits.hpp"
#include "apex/core/node_names.hpp"

#include <algorithm>
#include <cctype>

#include "edit_requests.hpp"
#include "edit_scope.hpp"
#include "graph_impl.hpp"
#include "live.hpp"
#include "names.hpp"
#include "node_state.hpp"
#include "yaml_text.hpp"

namespace apex {

using detail::EditScope;
using detail::NodeState;
using detail::Restructure;
using detail::ThreadGroup;

Graph::Impl::Impl(NodeRegistry registry)
    : registry_(std::move(registry)),
      edits_(std::make_shared<detail::EditRequests>([this](const Impl::NodePtr& node, const std::string& param,
                                                           const ParamValue& value) { applyRequested(node, param, value); },
                                                    [this] { return snapshot(); })) {
  group(kDefaultGroup);
}

void Graph::setHost(std::shared_ptr<const Host> host) {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  impl.host_ = std::move(host);
}

Graph::Impl::~Impl() {
  edits_->stop();  // first: a request applied now would edit what goes below
  stop();
  std::lock_guard<std::mutex> lock(edit_mutex_);
  clearLocked();
}

std::unique_lock<std::mutex> Graph::Impl::lockEdits() const {
  const ThreadGroup* caller = ThreadGroup::current();
  if (caller && caller->owner() == this) {
    throw std::logic_error("apex::Graph cannot be called from node code (process() or a slot handler) on thread group '" +
                           caller->name() + "': the call would wait for that very group. Call it from another thread.");
  }
  std::unique_lock<std::mutex> lock(edit_mutex_);
  edit_began_ = detail::ticks();
  return lock;
}

Graph::Impl::NodePtr Graph::Impl::find(const std::string& name) const {
  auto it = nodes_.find(name);
  return it == nodes_.end() ? nullptr : it->second;
}

Result<Graph::Impl::NodePtr> Graph::Impl::require(const std::string& name) const {
  if (auto n = find(name)) return n;
  return Status::error("no node named '" + name + "'");
}

ThreadGroup* Graph::Impl::group(const std::string& name) {
  auto& g = groups_[name];
  if (!g) {
    g = std::make_shared<ThreadGroup>(name, this);
    if (paused_) g->hold(true);
    if (tracing_) g->setTracing(true, kTraceFirings);
    if (running_) g->start();
  }
  return g.get();
}

Status Graph::Impl::roomFor(const std::string& group_name, std::size_t extra_nodes) const {
  if (!groups_.count(group_name) && groups_.size() >= kMaxGraphGroups)
    return Status::error("thread group '" + group_name + "': the graph has " + std::to_string(groups_.size()) +
                         " thread groups, the limit (each is a thread of the process)");
  if (nodes_.size() + extra_nodes > kMaxGraphNodes)
    return Status::error("the graph has " + std::to_string(nodes_.size()) + " nodes; " + std::to_string(extra_nodes) +
                         " more would pass the limit of " + std::to_string(kMaxGraphNodes));
  return Status::ok();
}

std::size_t Graph::Impl::connectionCount() const { return links_ + dormant_.size(); }

// ------------------------------------------------------------------ nodes

Result<std::string> Graph::Impl::addNode(const std::string& type_id, const std::string& wanted, const std::string& group_name) {
  return addNodeWith(type_id, wanted, group_name, {});
}

Result<std::string> Graph::Impl::addNodeWith(const std::string& type_id, const std::string& wanted, const std::string& group_name,
                                             const std::vector<std::pair<std::string, std::string>>& params) {
  auto lock = lockEdits();
  auto found = registry_.lookup(type_id);  // its id, or its name without the package prefix
  if (!found) return found.status();
  const std::shared_ptr<const NodeType> type = found.value();
  std::string name = wanted;
  if (name.empty()) {
    const std::string base = nodeBaseName(type->id);
    int& counter = name_counters_[base];
    do name = base + "_" + std::to_string(++counter);
    while (nodes_.count(name));
  } else if (auto why = checkNewPath(name); !why.empty()) {
    return Status::error(why);
  }
  const std::string gname = group_name.empty() ? kDefaultGroup : group_name;
  if (!validName(gname)) return Status::error("thread group name '" + gname + "' " + kNameRule);
  if (auto room = roomFor(gname, 1); !room) return Status::error("cannot add " + nodeLabel(name) + ": " + room.message());

  std::unique_ptr<Node> object;
  try {
    object = type->create();
  } catch (const std::exception& ex) {
    return Status::error("node type '" + type->id + "' failed to construct: " + ex.what());
  }
  auto state = std::make_shared<NodeState>(name, type, next_seq_++, revisions_);
  state->setHost(host_);
  state->joinGraph(revisions_, edits_);
  if (type->manifest->shape) {  // its ports for its default parameters
    auto iface = interfaceFor(*state, "", nullptr);
    if (!iface) return iface.status();
    state->setInterface(iface.value());
  }
  state->attach(std::move(object));
  if (auto st = presetParams(*state, params); !st) return st;  // before setup(): it sees them
  state->moveTo(group(gname));
  if (!subgraphs_.enabledAround(name)) state->setOuterEnabled(false);
  detail::initLiveness(state.get());
  EditScope scope;
  scope.added(state.get());
  state->post([](NodeState& n) { n.runSetup(); });
  order_[state->seq()] = state.get();
  nodes_[name] = std::move(state);
  bump();
  return name;
}

Result<std::string> Graph::Impl::addNode(const NodeDescription& d) {
  if (d.type == kSubgraphType) return addSubgraph(d);
  auto type = registry_.lookup(d.type);
  if (!type) return type.status();
  auto added = addNodeWith(type.value()->id, d.name, d.thread_group, d.parameters);
  if (!added) return added;
  const std::string name = added.value();
  auto undo = [&](const std::string& why) {
    (void)removeNode(name);
    return Status::error(why);
  };
  // The description's list is the exact set: a parameter interactive by default
  // but switched off before saving stays off.
  for (const auto& param : d.interactive)
    if (auto st = setInteractive(name, param, true); !st) return undo(st.message());
  for (const auto& spec : type.value()->manifest->params)
    if (std::find(d.interactive.begin(), d.interactive.end(), spec.name) == d.interactive.end())
      (void)setInteractive(name, spec.name, false);
  if (auto st = setEnabled(name, d.enabled); !st) return undo(st.message());
  if (!d.ui.empty())
    if (auto st = setUi(name, d.ui); !st) return undo(st.message());
  return name;
}

void Graph::Impl::detachAll(NodeState* n) {
  for (auto& e : n->edges()) removeEdge(e);  // each once: a second call finds it dead
  for (auto& e : n->events()) removeEvent(e);  // one to itself is listed twice, unlinked once
}

std::vector<NodeState*> Graph::Impl::dataReceivers(NodeState* n) {
  std::vector<NodeState*> out;
  n->forEachDataReceiver([&](const detail::Edge& e) { out.push_back(e.to); });
  return out;
}

void Graph::Impl::retire(NodeState* n, bool restructure) {
  std::vector<NodeState*> others = EditScope::neighbours(n);
  others.push_back(n);
  Restructure change(restructure ? dataReceivers(n) : std::vector<NodeState*>{}, others, restructure && ran_);
  detachAll(n);
  change.scope().forget(n);
  n->markRemoved();  // first: a notifyNewData() from now on cannot queue it again
  n->group()->unqueue(n);
}

Status Graph::Impl::removeNode(const std::string& name) {
  auto lock = lockEdits();
  if (subgraphs_.find(name)) {
    removeSubgraphLocked(name);
  } else {
    auto node = require(name);
    if (!node) return node.status();
    retire(node.value().get());
    order_.erase(node.value()->seq());
    nodes_.erase(name);
  }
  subgraphs_.dropExportsOf(name);
  bump();
  dormant_.erase(
      std::remove_if(dormant_.begin(), dormant_.end(), [&](const auto& c) { return c.from_node == name || c.to_node == name; }),
      dormant_.end());
  return Status::ok();
}

void Graph::Impl::clearLocked() {
  for (auto& [name, n] : nodes_) retire(n.get(), false);  // all go: nothing left to keep alive
  nodes_.clear();
  order_.clear();
  dormant_.clear();
  links_ = 0;
  subgraphs_.clear();
}

// ------------------------------------------------------------------ node settings

void Graph::Impl::changedDownstreamOf(NodeState* node, bool itself) {
  if (!rerun_on_edit_.load()) return;
  std::lock_guard<std::mutex> lock(changed_mutex_);
  changed_.push_back({node->weak_from_this(), itself, edit_began_});
  if (changed_.size() == 1)  // the first since the last walk: the next walk sees all that follow
    edits_->runAt(last_walk_ + kRerunGap, [this] { tellSourcesDownstreamChanged(); });
}

void Graph::Impl::tellSourcesDownstreamChanged() {
  auto lock = lockEdits();
  std::vector<Impl::ChangedAt> changed;
  {
    std::lock_guard<std::mutex> l(changed_mutex_);
    changed.swap(changed_);
    last_walk_ = std::chrono::steady_clock::now();
    walking_ = true;
  }
  struct Walked {  // however it ends
    Impl& g;
    ~Walked() {
      std::lock_guard<std::mutex> l(g.changed_mutex_);
      g.walking_ = false;
      g.walked_.notify_all();
    }
  } walked{*this};
  std::vector<Impl::NodePtr> alive;  // held while walking
  std::vector<NodeState*> at;
  std::int64_t newest = 0;
  for (const Impl::ChangedAt& c : changed) {
    newest = std::max(newest, c.tick);
    if (Impl::NodePtr n = c.node.lock(); n && !n->removed()) at.push_back(n.get()), alive.push_back(std::move(n));
  }
  std::vector<NodeState*> ups = detail::upstreamOf(at);
  for (const Impl::ChangedAt& c : changed)
    if (Impl::NodePtr n = c.node.lock(); c.itself && n && !n->removed()) ups.push_back(n.get());
  std::sort(ups.begin(), ups.end());
  ups.erase(std::unique(ups.begin(), ups.end()), ups.end());
  for (NodeState* up : ups) {
    if (up->isPlaceholder() || !up->isSource()) continue;  // a held frame starts at a source
    // None sent yet: it holds none. One it began to send after the last change went through the
    // graph as changed (a node connected before then got it, one tuned before then fires on it).
    if (up->lastSent() == 0 || up->lastSent() > newest) continue;
    // At most one re-send per pass of a frame through what it feeds (the sum of those nodes'
    // mean firing times; 40 ms to 0.5 s, so at most 25 re-runs a second, which the eye cannot
    // tell from more): a burst of edits re-runs a held frame a few times, never a queue of
    // stale runs, and the last run sees the last change.
    std::uint64_t pass_ns = 0;
    for (NodeState* down : detail::downstreamOf({up})) pass_ns += down->meanNs();
    const auto pass = std::chrono::nanoseconds(std::clamp<std::uint64_t>(pass_ns, 40'000'000, 500'000'000));
    up->downstreamChanged(pass);
  }
}

bool Graph::Impl::waitWalked(std::chrono::steady_clock::time_point deadline) const {
  std::unique_lock<std::mutex> l(changed_mutex_);
  return walked_.wait_until(l, deadline, [this] { return changed_.empty() && !walking_; });
}

Status Graph::Impl::setInteractive(const std::string& outer, const std::string& outer_param, bool on) {
  auto lock = lockEdits();
  auto at = subgraphs_.exportedParam(outer, outer_param);
  if (!at) return at.status();
  const std::string node = at.value().first, param = at.value().second;
  auto n = require(node);
  if (!n) return n.status();
  NodeState* s = n.value().get();
  const int i = s->findParam(param);
  if (i < 0)
    return Status::error(nodeLabel(node, s->typeId()) + " has no parameter '" + param +
                         "' (parameters: " + s->manifest().listParams() + ")");
  if (on && s->manifest().params[i].shapes_interface)
    return Status::error(portLabel("parameter", param, node) +
                         " decides the node's ports: it is set by edits only and cannot have ports");
  const auto& in = s->paramInEdge(i);
  const auto& outs = s->paramOutEdges(i);  // removeEdge takes each off this vector
  if (!on && (in || !outs.empty())) {
    std::vector<NodeState*> receivers;
    for (auto& e : outs)
      if (!e->to_param) receivers.push_back(e->to);
    std::vector<NodeState*> others = EditScope::neighbours(s);
    others.push_back(s);
    detail::Restructure change(receivers, others, ran_);
    if (in) removeEdge(in);
    while (!outs.empty()) removeEdge(outs.back());
  }
  s->setInteractive(i, on);
  bump();
  return Status::ok();
}

Status Graph::Impl::setEnabled(const std::string& node, bool enabled) {
  auto lock = lockEdits();
  if (auto sg = subgraphs_.find(node)) {  // all of its nodes, keeping their own settings
    sg->enabled = enabled;
    applyOuterEnabled(node);
    bump();
    return Status::ok();
  }
  auto n = require(node);
  if (!n) return n.status();
  NodeState& s = *n.value();
  s.setEnabled(enabled);
  if (s.type()) s.post([](NodeState& x) { x.applyEnabled(); });
  changedDownstreamOf(&s);
  return Status::ok();
}

Status Graph::setThreadGroup(const std::string& node, const std::string& group_name) {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  std::vector<std::string> names{node};
  if (impl.subgraphs_.find(node)) names = impl.nodesUnder(node);  // all of its nodes
  else if (auto n = impl.require(node); !n) return n.status();
  if (!validName(group_name)) return Status::error("thread group name '" + group_name + "' " + kNameRule);
  if (auto room = impl.roomFor(group_name); !room) return room;
  ThreadGroup* target = impl.group(group_name);
  for (const auto& name : names) {
    NodeState* s = impl.find(name).get();
    if (target == s->group()) continue;
    EditScope scope;
    scope.involve(s);
    scope.pause(target);
    s->moveTo(target);  // a placeholder keeps its group's name for a save
  }
  impl.bump();
  return Status::ok();
}

Status Graph::removeThreadGroup(const std::string& name) {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  if (name == kDefaultGroup) return Status::error("the thread group '" + name + "' cannot be removed");
  auto it = impl.groups_.find(name);
  if (it == impl.groups_.end()) return Status::error("no thread group '" + name + "'");
  for (auto& [seq, n] : impl.order_)
    if (n->group() == it->second.get()) return Status::error("thread group '" + name + "' still has node '" + n->name() + "'");
  it->second->pause();  // parked: a firing or wake-up that ends now is not counted as work
  if (!it->second->unused()) {
    it->second->resume();
    return Status::error("thread group '" + name + "' still has work posted (a timer or mail)");
  }
  it->second->stop();
  impl.groups_.erase(it);
  impl.bump();
  return Status::ok();
}

Status Graph::Impl::fireSlot(const std::string& outer, const std::string& outer_slot) {
  auto lock = lockEdits();
  if (subgraphs_.find(outer)) {  // every slot it stands for
    auto targets = subgraphs_.receivers(outer, outer_slot);
    if (!targets) return targets.status();
    for (const auto& [node, slot] : targets.value()) {
      lock.unlock();
      if (auto st = fireSlot(node, slot); !st) return st;
      lock.lock();
    }
    return Status::ok();
  }
  const std::string& node = outer;
  const std::string& slot = outer_slot;
  auto n = require(node);
  if (!n) return n.status();
  NodeState& s = *n.value();
  const auto& slots = s.manifest().slots;
  for (std::size_t i = 0; i < slots.size(); ++i) {
    if (slots[i].name != slot) continue;
    const int index = static_cast<int>(i);
    s.post([index](NodeState& x) { x.runSlot(index); });
    return Status::ok();
  }
  return Status::error(nodeLabel(node, s.typeId()) + " has no slot '" + slot + "' (slots: " + s.manifest().listSlots() + ")");
}

Status Graph::Impl::setUi(const std::string& node, const std::string& ui) {
  auto lock = lockEdits();
  auto sg = subgraphs_.find(node);
  auto n = require(node);
  if (!n && !sg) return n.status();
  if (auto st = detail::checkYamlText(ui); !st) return Status::error(nodeLabel(node) + ": UI metadata " + st.message());
  if (sg) {
    sg->ui = ui;
  } else {
    n.value()->setUi(ui);
  }
  bump();
  return Status::ok();
}

Status Graph::setTap(const std::string& outer, const std::string& outer_port, PortTap tap) {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  auto at = impl.subgraphs_.sender(outer, outer_port);
  if (!at) return at.status();
  const std::string node = at.value().first, port = at.value().second;
  auto n = impl.require(node);
  if (!n) return n.status();
  NodeState* s = n.value().get();
  EditScope scope;  // the group reads taps while firing
  scope.involve(s);
  const bool watching = static_cast<bool>(tap);
  if (const int i = s->findOutput(port); i >= 0) {
    s->setOutputTap(i, std::move(tap));
    if (watching) impl.changedDownstreamOf(s, true);  // a held frame: through the new tap at once
    return Status::ok();
  }
  if (const int i = s->findParam(port); i >= 0 && s->interactive(i)) {
    s->setParamTap(i, std::move(tap));
    if (watching) impl.changedDownstreamOf(s, true);
    return Status::ok();
  }
  return Status::error(nodeLabel(node, s->typeId()) + " has no output or interactive parameter '" + port +
                       "' (outputs: " + s->manifest().listOutputs() + ")");
}

// ------------------------------------------------------------------ reading

std::vector<NodeStats> Graph::nodeStats(double stall_after_s) const {
  const Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  std::vector<NodeState*> all;
  for (auto& [seq, n] : impl.order_) all.push_back(n);
  // The newest firing anywhere upstream of each node: data went in after it last fired.
  std::map<const NodeState*, std::int64_t> upstream;
  for (NodeState* n : detail::topological(all)) {
    std::int64_t newest = 0;
    n->forEachSender([&](const std::shared_ptr<detail::Edge>& e) {
      if (e && !e->to_param) newest = std::max({newest, e->from->lastFired(), upstream[e->from]});
    });
    upstream[n] = newest;
  }
  const std::int64_t now = detail::ticks();
  const double ns_per_tick = detail::nsPerTick();
  std::vector<NodeStats> out;
  for (NodeState* n : all) {
    out.push_back(n->stats());
    NodeStats& s = out.back();
    if (n->isPlaceholder()) s.error = "unknown node type '" + n->typeId() + "'";
    const std::int64_t last = n->lastFired();
    s.idle_s = double(now - last) * ns_per_tick * 1e-9;
    const bool stalled = s.idle_s > stall_after_s && (upstream[n] > last || !n->live());
    if ((stalled && !impl.paused_) || stall_after_s == 0) s.waiting_for = n->waitingFor();
  }
  return out;
}

std::vector<GroupStats> Graph::groupStats() const {
  const Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  std::vector<GroupStats> out;
  for (auto& [name, g] : impl.groups_) out.push_back(g->stats());
  return out;
}

std::shared_ptr<const NodeType> Graph::nodeType(const std::string& node) const {
  const Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  auto n = impl.find(node);
  return n ? n->type() : nullptr;
}

std::shared_ptr<const Manifest> Graph::nodeInterface(const std::string& node) const {
  const Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  if (auto sg = impl.subgraphs_.find(node)) return impl.facade(*sg);
  auto n = impl.find(node);
  return n && n->type() ? n->iface() : nullptr;
}

Node* Graph::nodeObject(const std::string& node) const {
  const Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  auto n = impl.find(node);
  return n ? n->object() : nullptr;
}

Result<NodeProfile> Graph::nodeProfile(const std::string& node) const {
  const Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  auto n = impl.require(node);
  if (!n) return n.status();
  return n.value()->profile();
}

Result<ParamValue> Graph::parameterValue(const std::string& outer, const std::string& outer_param) const {
  const Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  auto at = impl.subgraphs_.exportedParam(outer, outer_param);
  if (!at) return at.status();
  const std::string node = at.value().first, param = at.value().second;
  auto n = impl.require(node);
  if (!n) return n.status();
  const int i = n.value()->findParam(param);
  if (i < 0) return Status::error(nodeLabel(node) + " has no parameter '" + param + "'");
  return n.value()->requestedParam(i);
}

std::size_t Graph::size() const {
  const Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  return impl.nodes_.size();
}

}  // namespace apex
