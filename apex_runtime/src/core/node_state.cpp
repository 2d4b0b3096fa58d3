// The firing rule (see docs/architecture.md; its counters in readiness.hpp): a node fires when
// nothing blocks it; it reserves what it consumes, takes its inputs (freeing its sources), runs,
// and delivers.
#include "node_state.hpp"
#include "apex/core/node_names.hpp"
#include "names.hpp"

#include <algorithm>

namespace apex {
namespace detail {
namespace {

std::shared_ptr<const Manifest> manifestOf(const std::shared_ptr<const NodeType>& type) {
  static const auto kEmpty = std::make_shared<const Manifest>();
  return type ? type->manifest : kEmpty;
}

}  // namespace

NodeState::NodeState(std::string n, std::shared_ptr<const NodeType> t, std::uint64_t s, std::shared_ptr<Revisions> r)
    : name_(std::move(n)),
      type_(std::move(t)),
      iface_(manifestOf(type_)),
      seq_(s),
      revisions_(std::move(r)),
      driven_(iface_->source_mode != SourceMode::FreeRunning) {
  const Manifest& m = manifest();
  for (std::size_t i = 0; i < m.inputs.size(); ++i) inputs_.push_back(std::make_unique<InputState>());
  outputs_.resize(m.outputs.size());
  params_.resize(m.params.size());
  for (std::size_t i = 0; i < params_.size(); ++i) {
    params_[i].requested = params_[i].active = m.params[i].default_value;
    params_[i].interactive = m.params[i].interactive;
  }
  trigger_edges_.resize(m.triggers.size());
  slot_edges_.resize(m.slots.size());
  readiness_.start(driven());
  last_fired_.store(ticks());  // idle since added
}

NodeState::~NodeState() {
  // The node first, while every member is alive: its destructor may stop a thread of its own
  // that calls notifyNewData() until then (members go in reverse order: group_mutex_, declared
  // after `node`, would be gone; the test Races.RemovingADrivenNodeLeavesNothingQueued hung).
  node_.reset();
}

void NodeState::attach(std::unique_ptr<Node> object) {
  node_ = std::move(object);
  (void)resolveHandles(*node_, manifest());  // checked at registration against the default interface
  node_->state_.store(this, std::memory_order_release);
}

void NodeState::joinGraph(std::shared_ptr<Revisions> revisions, std::shared_ptr<EditRequests> edits) {
  revisions_ = std::move(revisions);
  edits_ = std::move(edits);
}

void NodeState::moveTo(ThreadGroup* g) {
  std::lock_guard<std::mutex> lock(group_mutex_);
  if (group_) group_->unqueue(this);
  group_ = g;
  if (!type_) placeholder_.thread_group = g->name();  // what it keeps for a save
}

void NodeState::markRemoved() {
  std::lock_guard<std::mutex> lock(group_mutex_);
  removed_ = true;
}

int NodeState::findInput(std::string_view n) const { return indexOf(manifest().inputs, n); }
int NodeState::findOutput(std::string_view n) const { return indexOf(manifest().outputs, n); }
int NodeState::findParam(std::string_view n) const { return indexOf(manifest().params, n); }
int NodeState::findTrigger(std::string_view n) const { return indexOf(manifest().triggers, n); }

std::string NodeState::error() const { return shared_.lock()->error; }

void NodeState::setEnabled(bool on) {
  auto shared = shared_.lock();
  shared->enabled = on;
  placeholder_.enabled = on;
}

void NodeState::setOuterEnabled(bool on) { shared_.lock()->outer_enabled = on; }

std::string NodeState::ui() const { return shared_.lock()->ui; }

void NodeState::setUi(std::string text) { shared_.lock()->ui = std::move(text); }

// ---------------------------------------------------------------- counting

bool NodeState::isSource() const {
  if (readiness_.connectedInputs() > 0) return false;
  for (const auto& in : manifest().inputs)
    if (!in.optional) return false;
  return true;
}

int NodeState::gates() const {
  if (!type_ || !live_) return 1;  // a placeholder, or a node cut off from every source, never fires
  if (readiness_.liveInputs() > 0) return 0;
  if (!active_enabled_) return 1;  // a disabled source stays quiet
  if (!driven() && readiness_.countedReceivers() == 0) return 1;  // a free-running source with no receiver
  return 0;
}

int NodeState::structuralBlockers() {
  int p = gates();
  for (auto& in : inputs_)
    if (in->edge && in->edge->live && !in->full.load(std::memory_order_acquire)) ++p;
  for (auto& out : outputs_)
    for (auto& e : out.edges) p += e->unread.load(std::memory_order_acquire) ? 1 : 0;
  return p;
}

void NodeState::updateLive() {
  int live_inputs = 0;
  for (auto& in : inputs_) {
    if (!in->edge) continue;
    in->edge->live = in->edge->from->live_;
    live_inputs += in->edge->live ? 1 : 0;
  }
  readiness_.setLiveInputs(live_inputs);
  live_ = type_ && (isSource() || live_inputs > 0);
}

void NodeState::flushPorts() {
  for (auto& in : inputs_) {
    // A value from a parameter output is a setting, not a frame: it stays until replaced.
    if (in->edge && !in->edge->counted()) continue;
    std::lock_guard<std::mutex> lock(in->m);
    in->msg = Message();
    in->full.store(false, std::memory_order_release);
    if (in->edge) in->edge->unread.store(false, std::memory_order_release);
  }
  for (auto& out : outputs_)
    for (auto& e : out.edges) e->unread.store(false, std::memory_order_release);
}

std::string NodeState::waitingFor() const {
  if (!type_) return "";
  if (!live_) {
    for (std::size_t i = 0; i < inputs_.size(); ++i)
      if (!manifest().inputs[i].optional && !inputs_[i]->edge)
        return "cut off: input '" + manifest().inputs[i].name + "' is not connected";
    return "cut off: no source reaches its inputs";
  }
  // An unread output blocks whatever the inputs hold: say it first.
  for (std::size_t i = 0; i < outputs_.size(); ++i)
    for (auto& e : outputs_[i].edges)
      if (e->unread.load(std::memory_order_acquire))
        return "waiting for '" + e->to->name() + "' to read '" + manifest().outputs[i].name + "'";
  for (std::size_t i = 0; i < inputs_.size(); ++i) {
    const Edge* e = inputs_[i]->edge.get();
    if (e && e->live && !inputs_[i]->full.load(std::memory_order_acquire))
      return "waiting for input '" + manifest().inputs[i].name + "' from '" + e->from->name() + "'";
  }
  if (driven() && !has_data_.load(std::memory_order_acquire)) return "waiting for new data";
  return "";
}

void NodeState::correctBlockers(int delta) {
  if (readiness_.correct(delta)) group_->push(this);
}

void NodeState::adjust(int delta) {
  if (delta > 0) readiness_.block(delta);
  if (delta < 0) unblock(-delta);
}

// ---------------------------------------------------------------- firing

[[gnu::always_inline]] inline void NodeState::take(InputState& in, bool optional, bool& skip, bool& read_later) {
  Edge* e = in.edge.get();
  if (!e || !e->live) {  // unconnected or cut off: Nothing
    in.current = Message();
  } else if (e->counted()) {  // exclusive by the firing rule: no lock
    in.current = std::move(in.msg);  // leaves Nothing behind
    in.full.store(false, std::memory_order_release);
    if (e->read_after_firing) {  // the source's newest then, not a frame that waits while we work
      read_later = true;
    } else {
      e->unread.store(false, std::memory_order_release);  // a slot of the sender reads it (sendFromSlot)
      e->from->unblock(1, group_);  // the source may fire again while we work
    }
  } else {
    std::lock_guard<std::mutex> lock(in.m);
    in.current = std::move(in.msg);
    in.full.store(false, std::memory_order_relaxed);
  }
  if (in.current.isNothing() && !optional) skip = true;
}

[[gnu::always_inline]] inline void NodeState::reserve() {
  // Every condition this firing consumes: inputs become empty, receivers get an unread
  // message, a driven source uses up its data. has_data_ is cleared first: a notifyNewData()
  // arriving meanwhile then counts for the next firing (its release finds nothing to release
  // yet and drives the count below zero; the reservation then lands on zero exactly when that
  // release was the only thing missing).
  if (!driven()) return readiness_.reserveAtZero();  // nothing else can release it now
  has_data_.store(false, std::memory_order_release);
  if (readiness_.reserve(true)) group_->runNext(this);  // new data came between the two lines
}

[[gnu::always_inline]] inline NodeState::Firing NodeState::takeInputs() {
  Firing f;
  f.skip = !active_enabled_;
  for (std::size_t i = 0; i < inputs_.size(); ++i) {
    take(*inputs_[i], manifest().inputs[i].optional, f.skip, f.read_later);
    const Message& m = inputs_[i]->current;
    f.end = f.end || m.isEndOfSequence();
    f.data = f.data || (!m.isNothing() && !m.isEndOfSequence());
    if (m.frame() > f.frame) f.frame = m.frame();
  }
  return f;
}

[[gnu::always_inline]] inline void NodeState::run(const Firing& f) {
  bool ok = true;
  in_handler_ = true;
  if (f.end && active_enabled_) {
    ok = guarded("at the end of a sequence", [this] { node_->endOfSequence(); });
  } else if (f.end) {
    for (auto& out : outputs_) out.pending = Message::endOfSequence();  // a disabled node passes the end on
  } else if (!f.skip) {
    ok = guarded("", [this] { node_->process(); });
    if (!ok || reported_) slot_error_ = false;  // the error shown is this firing's own
    else if (!slot_error_ && has_error_.load(std::memory_order_relaxed)) clearError();
  }
  in_handler_ = false;
  reported_ = false;
  if (!ok)  // a failed firing sends Nothing; a failed end of a sequence still ends it downstream
    for (auto& out : outputs_) out.pending = f.end ? Message::endOfSequence() : Message();
}

[[gnu::always_inline]] inline void NodeState::deliverTo(const std::shared_ptr<Edge>& edge, Message&& m, ThreadGroup* here) {
  Edge& e = *edge;
  if (e.to_param || !e.counted()) return deliverSlow(edge, std::move(m), here);
  // A counted data edge (the common case, inlined): the receiver took the last one, the slot is ours.
  NodeState* to = e.to;
  InputState& in = *to->inputs_[e.to_index];
  in.msg = std::move(m);
  in.full.store(true, std::memory_order_relaxed);
  e.unread.store(true, std::memory_order_relaxed);
  to->unblock(1, here);  // releases the writes above to whoever fires `to`
}

[[gnu::always_inline]] inline void NodeState::deliverOutputs(const Firing& f) {
  bool data = f.data;
  nameFrames(f.frame);
  for (auto& out : outputs_) {
    if (!out.pending.isNothing() && !out.pending.isEndOfSequence()) data = true, out.sent.add();
    if (out.tap) out.tap(out.pending);
    const std::size_t n = out.edges.size();
    if (n == 0) {
      out.pending = Message();
      continue;
    }
    for (std::size_t k = 0; k + 1 < n; ++k) deliverTo(out.edges[k], Message(out.pending), group_);
    deliverTo(out.edges[n - 1], std::move(out.pending), group_);  // leaves Nothing behind
  }
  last_had_data_ = data;
  for (std::size_t i = 0; i < params_.size(); ++i)
    if (!params_[i].out_edges.empty() || params_[i].tap) publishParam(static_cast<int>(i), group_);
}

// The steps of a firing are functions of their own for the reader, inlined into fireIfReady:
// as calls they cost ~5-10% per hop (bench/core_bench.cpp, old and new interleaved).
bool NodeState::fireIfReady() {
  if (!readiness_.ready() || removed_ || !live_) return false;
  if (params_dirty_.load(std::memory_order_acquire)) applyParams();
  reserve();
  Firing f = takeInputs();
  run(f);
  deliverOutputs(f);
  for (auto& in : inputs_) in->current = Message();
  if (f.read_later) readAfterFiring();
  if (!held_triggers_.empty()) releaseTriggers();  // checked here: most firings need neither call
  if (!f.skip && !f.end && !trigger_edges_[kProcessedIndex].empty()) fireTrigger(kProcessedIndex);
  return true;
}

void NodeState::readAfterFiring() {
  for (auto& in : inputs_) {
    Edge* e = in->edge.get();
    if (e && e->read_after_firing && e->unread.exchange(false, std::memory_order_acq_rel)) e->from->unblock(1, group_);
  }
}

void NodeState::deliver(const std::shared_ptr<Edge>& edge, Message m, ThreadGroup* here) { deliverTo(edge, std::move(m), here); }

void NodeState::deliverSlow(const std::shared_ptr<Edge>& edge, Message&& m, ThreadGroup* here) {
  Edge& e = *edge;
  NodeState* to = e.to;
  if (e.to_param) {  // the mail holds the edge: a disconnect marks it dead, never frees it under us
    if (m.isNothing() || m.isEndOfSequence()) {  // no value to set: read at once, no mail
      if (e.counted()) unblock(1, here);
      return;
    }
    if (e.counted()) {  // the sender waits until it is read: one mail at a time
      e.unread.store(true, std::memory_order_release);
      to->post([edge, m = std::move(m)](NodeState& n) { n.receiveParam(*edge, m); });
      return;
    }
    // From a parameter output, which never waits and may send at every firing of a fast node:
    // the newest value waits on the edge and one mail applies it. A mail per value would fill a
    // slower group's mailbox without bound and keep its nodes from firing.
    {
      std::lock_guard<std::mutex> lock(e.newest_m);
      const bool mail_pending = !e.newest.isNothing();
      e.newest = std::move(m);
      if (mail_pending) return;
    }
    to->post([edge](NodeState& n) {
      Message newest;
      {
        std::lock_guard<std::mutex> lock(edge->newest_m);
        newest = std::move(edge->newest);  // leaves Nothing: the next value posts again
      }
      n.receiveParam(*edge, newest);
    });
    return;
  }
  InputState& in = *to->inputs_[e.to_index];
  bool was_full;
  {
    std::lock_guard<std::mutex> lock(in.m);
    was_full = in.full.load(std::memory_order_relaxed);
    in.msg = std::move(m);
    in.full.store(true, std::memory_order_relaxed);
  }
  // A parameter output may overwrite a value not yet read. A dead edge is not counted
  // (a cut-off sender publishes on parameter changes): it must not release anything.
  if (!was_full && e.live) to->unblock(1, here);
}

void NodeState::setError(std::string text) {
  bool report = false;
  {
    auto shared = shared_.lock();
    if (shared->error == text) return;  // the same failure again: already reported
    // A failure that names its input (a stamp, a value) differs at every firing: the state always
    // shows the newest, the log takes the first and then one every kErrorLogInterval, so a node
    // failing at camera rate does not flood the console.
    const auto now = std::chrono::steady_clock::now();
    report = !has_error_.load(std::memory_order_relaxed) || now - shared->error_logged >= kErrorLogInterval;
    if (report) shared->error_logged = now;
    shared->error = text;
    has_error_.store(true, std::memory_order_relaxed);
  }
  revisions_->shown();
  if (report) log(LogLevel::Error, name_, text);
}

void NodeState::clearError() {
  {
    auto shared = shared_.lock();
    shared->error.clear();
    has_error_.store(false, std::memory_order_relaxed);
  }
  slot_error_ = false;
  revisions_->shown();
  log(LogLevel::Info, name_, "recovered");
}

// ---------------------------------------------------------------- mail

void NodeState::post(std::function<void(NodeState&)> fn) { group_->post(Mail{shared_from_this(), std::move(fn)}); }

void NodeState::postFromAnywhere(std::function<void(NodeState&)> fn) {
  auto self = weak_from_this().lock();
  if (!self) return;  // being destroyed (the node's own members may call in while they stop)
  std::lock_guard<std::mutex> lock(group_mutex_);  // against a move to another group
  if (!group_) return;
  // Posted even if the node was removed meanwhile: its group skips the mail, and the reference
  // taken here goes on that thread. Dropped here, it could be the last one, destroying the node on
  // the caller's thread: an Optimizer's copy's, which its destructor would have to join.
  group_->post(Mail{std::move(self), std::move(fn)});
}

void NodeState::notifyNewData() {
  if (!driven()) return;  // only a driven source waits for data (reserveAtZero relies on it)
  std::lock_guard<std::mutex> lock(group_mutex_);
  if (removed_ || !group_) return;
  if (!has_data_.exchange(true, std::memory_order_acq_rel)) unblock(1);
}

void NodeState::notifyAfter(double seconds) {
  const auto when = std::chrono::steady_clock::now() +
                    std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
  std::lock_guard<std::mutex> lock(group_mutex_);
  if (!removed_ && group_) group_->notifyAt(when, shared_from_this());
}

void NodeState::publishParam(int index, ThreadGroup* here) {
  if (params_[index].out_edges.empty() && !params_[index].tap) return;
  Message m = toMessage(params_[index].active);
  for (auto& e : params_[index].out_edges) deliver(e, m, here);
  if (params_[index].tap) params_[index].tap(m);
}

void NodeState::runSetup() {
  applyParams();  // setup() sees the values the node was added with
  try {
    node_->setup();
  } catch (const std::exception& ex) {
    setError(nodeLabel(name_, type_->id) + " failed to set up: " + ex.what());
  }
}

void NodeState::applyEnabled() {
  bool want;
  {
    auto shared = shared_.lock();
    want = shared->enabled && shared->outer_enabled;
  }
  if (want == active_enabled_) return;
  const int before = gates();
  active_enabled_ = want;
  adjust(gates() - before);
  revisions_->shown();
}

void NodeState::downstreamChanged(std::chrono::steady_clock::duration interval) {
  auto run = [](NodeState& n) { n.runDownstreamChanged(); };
  const auto now = std::chrono::steady_clock::now();
  auto shared = shared_.lock();
  if (shared->resend_due) return;  // the one set for later sees this change too
  if (now >= shared->last_resend + interval) {
    shared->last_resend = now;
    post(run);
    return;
  }
  shared->resend_due = true;
  group_->at(shared->last_resend + interval, Mail{shared_from_this(), [](NodeState& n) {
                                                    {
                                                      auto s = n.shared_.lock();
                                                      s->resend_due = false;
                                                      s->last_resend = std::chrono::steady_clock::now();
                                                    }
                                                    n.runDownstreamChanged();  // timers run on the node's group
                                                  }});
}

void NodeState::runDownstreamChanged() {
  if (removed_) return;
  try {
    node_->downstreamChanged();
  } catch (const std::exception& ex) {
    setError(nodeLabel(name_, type_->id) + " failed to re-send after a change downstream: " + ex.what());
  }
}

}  // namespace detail
}  // namespace apex
