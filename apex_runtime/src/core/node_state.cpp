// The firing rule (see docs/architecture.md): a node fires when `blockers` is
// zero; it takes its inputs first (freeing its sources), processes, publishes.
#include "node_state.hpp"

#include <algorithm>

namespace apex {
namespace detail {
namespace {

const Manifest& manifestOf(const std::shared_ptr<const NodeType>& type) {
  static const Manifest kEmpty;
  return type ? *type->manifest : kEmpty;
}

template <class T>
int indexOf(const std::vector<T>& items, const std::string& n) {
  for (std::size_t i = 0; i < items.size(); ++i) if (items[i].name == n) return static_cast<int>(i);
  return -1;
}

}  // namespace

NodeState::NodeState(std::string n, std::shared_ptr<const NodeType> t, std::uint64_t s,
                     std::shared_ptr<std::atomic<std::uint64_t>> r)
    : name(std::move(n)), type(std::move(t)), manifest(manifestOf(type)), seq(s), revision(std::move(r)) {
  for (std::size_t i = 0; i < manifest.inputs.size(); ++i) inputs.push_back(std::make_unique<InputState>());
  outputs.resize(manifest.outputs.size());
  params.resize(manifest.params.size());
  for (std::size_t i = 0; i < params.size(); ++i) {
    params[i].requested = params[i].active = manifest.params[i].default_value;
    params[i].interactive = manifest.params[i].interactive;
  }
  trigger_edges.resize(manifest.triggers.size());
  slot_edges.resize(manifest.slots.size());
  blockers.store(driven() ? 1 : 0);  // a driven source waits for its first notifyNewData()
}

NodeState::~NodeState() = default;

int NodeState::findInput(const std::string& n) const { return indexOf(manifest.inputs, n); }
int NodeState::findOutput(const std::string& n) const { return indexOf(manifest.outputs, n); }
int NodeState::findParam(const std::string& n) const { return indexOf(manifest.params, n); }
int NodeState::findTrigger(const std::string& n) const { return indexOf(manifest.triggers, n); }

std::string NodeState::error() const {
  std::lock_guard<std::mutex> lock(state_mutex);
  return error_;
}

// ---------------------------------------------------------------- counting

int NodeState::gates() const {
  if (!type) return 1;  // a placeholder never fires
  for (std::size_t i = 0; i < inputs.size(); ++i)
    if (!inputs[i]->edge && !manifest.inputs[i].optional) return 1;  // waits for a source
  if (connected_inputs > 0) return 0;
  if (!active_enabled_) return 1;                    // a disabled source stays quiet
  if (!driven() && counted_out == 0) return 1;       // a free-running source with no receiver
  return 0;
}

int NodeState::structuralBlockers() {
  int p = gates();
  for (auto& in : inputs) {
    if (!in->edge) continue;
    std::lock_guard<std::mutex> lock(in->m);
    p += in->full ? 0 : 1;
  }
  for (auto& out : outputs)
    for (auto& e : out.edges) p += e->unread.load(std::memory_order_acquire) ? 1 : 0;
  return p;
}

void NodeState::unblock(int k) {
  if (blockers.fetch_sub(k, std::memory_order_acq_rel) == k) group->push(this);
}

void NodeState::adjust(int delta) {
  if (delta > 0) blockers.fetch_add(delta, std::memory_order_acq_rel);
  if (delta < 0) unblock(-delta);
}

// ---------------------------------------------------------------- firing

bool NodeState::fireIfReady() {
  if (blockers.load(std::memory_order_acquire) != 0 || removed) return false;
  if (params_dirty_.load(std::memory_order_acquire)) applyParams();
  // Reserve every condition this firing consumes: inputs become empty, receivers
  // get an unread message, a driven source uses up its data.
  blockers.fetch_add(connected_inputs + counted_out + (driven() ? 1 : 0), std::memory_order_acq_rel);
  if (driven()) has_data.store(false, std::memory_order_release);

  bool skip = !active_enabled_;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    InputState& in = *inputs[i];
    if (!in.edge) {
      in.current = Message();
      continue;
    }
    Edge* e = in.edge.get();
    {
      std::lock_guard<std::mutex> lock(in.m);
      in.current = std::move(in.msg);
      in.msg = Message();
      in.full = false;
      e->unread.store(false, std::memory_order_release);
    }
    if (e->counted()) e->from->unblock(1);  // the source may fire again while we work
    if (in.current.isNothing() && !manifest.inputs[i].optional) skip = true;
  }

  for (auto& out : outputs) out.pending = Message();
  if (!skip) {
    try {
      node->process();
      if (has_error_.load(std::memory_order_relaxed)) clearError();
    } catch (const std::exception& ex) {
      setError("node '" + name + "' (" + type->id + ") threw: " + ex.what());
    } catch (...) {
      setError("node '" + name + "' (" + type->id + ") threw an exception that is not a std::exception");
    }
    if (has_error_.load(std::memory_order_relaxed))
      for (auto& out : outputs) out.pending = Message();
  }
  for (auto& out : outputs) {
    for (auto& e : out.edges) deliver(e, out.pending);
    if (out.tap) out.tap(out.pending);
  }
  for (std::size_t i = 0; i < params.size(); ++i) publishParam(static_cast<int>(i));
  for (auto& in : inputs) in->current = Message();
  for (auto& out : outputs) out.pending = Message();
  if (!skip) fireTrigger(0);  // "processed"
  return true;
}

void NodeState::recordFiring(std::int64_t ns) {
  const auto n = firings_.fetch_add(1, std::memory_order_relaxed) + 1;
  (void)n;
  last_ns_.store(ns, std::memory_order_relaxed);
  total_ns_.fetch_add(ns, std::memory_order_relaxed);
  if (static_cast<std::uint64_t>(ns) > max_ns_.load(std::memory_order_relaxed)) max_ns_.store(ns, std::memory_order_relaxed);
}

NodeStats NodeState::stats() const {
  NodeStats s;
  s.name = name;
  s.firings = firings_.load(std::memory_order_relaxed);
  s.last_ns = last_ns_.load(std::memory_order_relaxed);
  s.max_ns = max_ns_.load(std::memory_order_relaxed);
  s.mean_ns = s.firings ? total_ns_.load(std::memory_order_relaxed) / s.firings : 0;
  std::lock_guard<std::mutex> lock(state_mutex);
  s.error = error_;
  s.enabled = enabled;
  return s;
}

void NodeState::setOutput(int index, Message m) { outputs[index].pending = std::move(m); }

void NodeState::deliver(const std::shared_ptr<Edge>& edge, const Message& m) {
  Edge& e = *edge;
  NodeState* to = e.to;
  if (e.to_param) {  // the mail holds the edge: a disconnect marks it dead, never frees it under us
    if (e.counted()) e.unread.store(true, std::memory_order_release);
    to->post([edge, m](NodeState& n) { n.receiveParam(*edge, m); });
    return;
  }
  InputState& in = *to->inputs[e.to_index];
  bool was_full;
  {
    std::lock_guard<std::mutex> lock(in.m);
    was_full = in.full;
    in.msg = m;
    in.full = true;
    if (e.counted()) e.unread.store(true, std::memory_order_release);
  }
  if (!was_full) to->unblock(1);  // a parameter output may overwrite a value not yet read
}

void NodeState::setError(std::string text) {
  bool report = false;
  {
    std::lock_guard<std::mutex> lock(state_mutex);
    if (error_ == text) return;  // the same failure again: already reported
    // A failure that names its input (a stamp, a value) differs at every firing: the state always
    // shows the newest, the log takes the first and then one every kErrorLogInterval, so a node
    // failing at camera rate does not flood the console.
    const auto now = std::chrono::steady_clock::now();
    report = !has_error_.load(std::memory_order_relaxed) || now - error_logged_ >= kErrorLogInterval;
    if (report) error_logged_ = now;
    error_ = text;
    has_error_.store(true, std::memory_order_relaxed);
  }
  revision->fetch_add(1, std::memory_order_relaxed);
  if (report) log(LogLevel::Error, name, text);
}

void NodeState::clearError() {
  {
    std::lock_guard<std::mutex> lock(state_mutex);
    error_.clear();
    has_error_.store(false, std::memory_order_relaxed);
  }
  revision->fetch_add(1, std::memory_order_relaxed);
  log(LogLevel::Info, name, "recovered");
}

// ---------------------------------------------------------------- mail

void NodeState::post(std::function<void(NodeState&)> fn) { group->post(Mail{shared_from_this(), std::move(fn)}); }

void NodeState::notifyNewData() {
  std::lock_guard<std::mutex> lock(group_mutex);
  if (removed || !group) return;
  if (!has_data.exchange(true, std::memory_order_acq_rel)) unblock(1);
}

void NodeState::notifyAfter(double seconds) {
  const auto when = std::chrono::steady_clock::now() +
                    std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
  std::lock_guard<std::mutex> lock(group_mutex);
  if (!removed && group) group->notifyAt(when, shared_from_this());
}

void NodeState::requestParam(int index, ParamValue v) {
  bool post_now = false;
  {
    std::lock_guard<std::mutex> lock(state_mutex);
    params[index].requested = std::move(v);
    params_dirty_.store(true, std::memory_order_release);
    post_now = !apply_posted_;
    apply_posted_ = true;
  }
  if (post_now) post([](NodeState& n) { n.applyParams(); });
}

void NodeState::applyParams() {
  std::vector<int> changed;
  {
    std::lock_guard<std::mutex> lock(state_mutex);
    apply_posted_ = false;
    params_dirty_.store(false, std::memory_order_relaxed);
    for (std::size_t i = 0; i < params.size(); ++i) {
      if (params[i].requested == params[i].active) continue;
      params[i].active = params[i].requested;
      changed.push_back(static_cast<int>(i));
    }
  }
  for (int i : changed) {
    try {
      node->parameterChanged(manifest.params[i].name);
    } catch (const std::exception& ex) {
      setError("node '" + name + "' (" + type->id + ") failed to apply parameter '" + manifest.params[i].name +
               "': " + ex.what());
    }
    publishParam(i);  // a parameter output carries every change
  }
  if (!changed.empty()) revision->fetch_add(1, std::memory_order_relaxed);
}

void NodeState::publishParam(int index) {
  if (params[index].out_edges.empty() && !params[index].tap) return;
  Message m = toMessage(params[index].active);
  for (auto& e : params[index].out_edges) deliver(e, m);
  if (params[index].tap) params[index].tap(m);
}

void NodeState::receiveParam(Edge& edge, const Message& m) {
  if (edge.dead) return;
  if (!m.isNothing()) {
    auto value = fromMessage(manifest.params[edge.to_index], m);
    if (value) {
      requestParam(edge.to_index, value.value());
      applyParams();
    } else {
      setError("node '" + name + "': parameter input refused a value: " + value.message());
    }
  }
  if (edge.counted()) {
    edge.unread.store(false, std::memory_order_release);
    edge.from->unblock(1);
  }
}

void NodeState::runSetup() {
  applyParams();  // setup() sees the values the node was added with
  try {
    node->setup();
  } catch (const std::exception& ex) {
    setError("node '" + name + "' (" + type->id + ") failed to set up: " + ex.what());
  }
}

void NodeState::applyEnabled() {
  bool want;
  {
    std::lock_guard<std::mutex> lock(state_mutex);
    want = enabled;
  }
  if (want == active_enabled_) return;
  const int before = gates();
  active_enabled_ = want;
  adjust(gates() - before);
  revision->fetch_add(1, std::memory_order_relaxed);
}

void NodeState::runSlot(int slot) {
  if (slot == 0 || slot == 1) {  // built-in enable / disable
    {
      std::lock_guard<std::mutex> lock(state_mutex);
      enabled = slot == 0;
    }
    applyEnabled();
    return;
  }
  try {
    manifest.slots[slot].handler(*node);
  } catch (const std::exception& ex) {
    setError("node '" + name + "' (" + type->id + ") slot '" + manifest.slots[slot].name + "' threw: " + ex.what());
  }
}

void NodeState::fireTrigger(int trigger) {
  for (auto& e : trigger_edges[trigger]) {
    const int slot = e->slot;
    e->to->post([slot](NodeState& n) { n.runSlot(slot); });
  }
}

}  // namespace detail
}  // namespace apex
