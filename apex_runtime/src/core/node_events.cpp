// Events on the group thread: slots (what a handler publishes goes out as a firing's messages
// do), triggers held until the messages of their firing or slot have left, and what an output
// feeds (see docs/architecture.md, "Sequences, events in order, and the tuning loop").
#include "node_state.hpp"

#include "apex/core/node_names.hpp"

namespace apex {
namespace detail {

void NodeState::runSlot(int slot) {
  if (slot == kEnableIndex || slot == kDisableIndex) {  // built-in
    shared_.lock()->enabled = slot == kEnableIndex;
    applyEnabled();
    return;
  }
  if (slot >= static_cast<int>(manifest().slots.size())) return;  // posted before an interface change
  const auto& handler = manifest().slots[slot].handler;
  const bool ok = runHandler("slot '" + manifest().slots[slot].name + "'", [&] { handler(*node_); });
  if (!ok) slot_error_ = true;
  else if (slot_error_ && has_error_.load(std::memory_order_relaxed)) clearError();
}

bool NodeState::runHandler(const std::string& what, const std::function<void()>& fn) {
  if (!node_) return false;  // a placeholder
  in_handler_ = true;
  const bool ok = guarded(what.c_str(), fn);
  const bool failed = !ok || reported_;
  in_handler_ = false;
  reported_ = false;
  if (ok && !sendFromSlot(what)) held_triggers_.clear();  // its events would act on values that did not go out
  if (!ok) {
    for (auto& out : outputs_) out.pending = Message();
    held_triggers_.clear();
  }
  releaseTriggers();
  return !failed;
}

bool NodeState::sendFromSlot(const std::string& slot) {
  bool all = true;
  nameFrames(0);
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    OutputState& out = outputs_[i];
    if (out.pending.isNothing()) continue;
    Message m = std::move(out.pending);
    out.pending = Message();
    // A counted edge into an input may carry one message at a time: the slot cannot send while a
    // receiver still holds the last one (the firing rule's exclusivity of the receiver's input).
    // Into a parameter a value is a setting, not a frame: one sent while the last is still in the
    // receiver's mail goes behind it (its mailbox keeps their order), uncounted; never refused.
    // (The Optimizer's apply_best right after its run gave the old values back: a busy group had
    // not applied them yet, and the best values were refused.)
    // An input whose sender is cut off from every source does not count it: nothing to send there.
    auto reaches = [](const Edge& e) { return e.to_param || e.live; };
    const Edge* busy = nullptr;
    for (auto& e : out.edges)
      if (!e->to_param && e->unread.load(std::memory_order_acquire)) busy = e.get();
    if (busy) {
      setError(nodeLabel(name_, type_->id) + " " + slot + " published on output '" + manifest().outputs[i].name + "' while '" +
               busy->to->name() + "' had not read its last message: not sent");
      all = false;
      continue;
    }
    // Which edges wait for their receiver, decided once: a receiver may read its last value meanwhile.
    // (Only this thread sets `unread`: an edge seen read stays so.)
    std::vector<char> behind(out.edges.size(), 0);
    int counted = 0;
    for (std::size_t k = 0; k < out.edges.size(); ++k) {
      const Edge& e = *out.edges[k];
      if (!e.counted() || !reaches(e)) continue;
      behind[k] = e.to_param && e.unread.load(std::memory_order_acquire);
      counted += behind[k] ? 0 : 1;
    }
    if (out.tap) out.tap(m);
    if (!m.isEndOfSequence()) out.sent.add();
    readiness_.block(counted);  // released as the receivers read, as after a firing
    for (std::size_t k = 0; k < out.edges.size(); ++k) {
      const auto& e = out.edges[k];
      if (!reaches(*e)) continue;
      if (behind[k]) e->to->post([e, m](NodeState& n) { n.receiveParam(*e, m, false); });
      else deliver(e, m);
    }
  }
  return all;
}

void NodeState::reportError(const std::string& text) {
  setError(nodeLabel(name_, typeId()) + ": " + text);
  reported_ = in_handler_;  // outside a firing there is nothing to keep it from clearing
}

void NodeState::releaseTriggers() {
  if (held_triggers_.empty()) return;  // every firing passes here
  std::vector<int> held;
  held.swap(held_triggers_);
  for (int t : held) fireTrigger(t);
}

std::vector<ParamTarget> NodeState::parameterTargets(int index) const {
  std::vector<ParamTarget> out;
  for (const auto& e : outputs_[index].edges) {
    if (!e->to_param || e->dead) continue;
    NodeState& to = *e->to;
    auto lock = to.shared_.lock();  // its interface and values change under it
    out.push_back({to.name_, to.manifest().params[e->to_index], to.params_[e->to_index].requested});
  }
  return out;
}

void NodeState::fireTrigger(int trigger) {
  if (in_handler_) {
    held_triggers_.push_back(trigger);
    return;
  }
  const auto send = [&](const std::shared_ptr<EventEdge>& e) {
    // enable/disable set a state: one dropped would leave the node in the wrong one for good
    const bool sets_state = e->slot == kEnableIndex || e->slot == kDisableIndex;
    if (e->pending.fetch_add(1, std::memory_order_relaxed) >= kMaxPendingEvents && !sets_state) {  // the slot is far behind
      e->pending.fetch_sub(1, std::memory_order_relaxed);
      if (e->dropped.fetch_add(1, std::memory_order_relaxed) == 0)
        log(LogLevel::Warn, e->to->name(),
            nodeLabel(e->to->name()) + " slot '" + e->to->manifest().slots[e->slot].name + "' runs slower than " +
                nodeLabel(name_) + " fires '" + manifest().triggers[trigger].name + "': with " +
                std::to_string(kMaxPendingEvents) + " events waiting, further ones are dropped until it catches up");
      return;
    }
    e->to->post([e](NodeState& n) {
      e->pending.fetch_sub(1, std::memory_order_relaxed);
      n.runSlot(e->slot);
    });
  };
  // Sources last: what a source sends after its event (a player's restart) finds every node
  // downstream already told (a mean's reset), since their mail is posted before its first frame is.
  for (const auto& e : trigger_edges_[trigger])
    if (!e->to_source) send(e);
  for (const auto& e : trigger_edges_[trigger])
    if (e->to_source) send(e);
}

}  // namespace detail
}  // namespace apex
