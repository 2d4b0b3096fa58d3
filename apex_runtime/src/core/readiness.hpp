// The firing rule's counters for one node, in one place: every write of them is a named
// transition below (docs/architecture.md, "The firing rule").
//
// A node fires when `blockers` is zero. It counts what keeps the node from firing: each live
// input that is empty, each receiver that has not read its last message (a counted edge), a
// driven source's missing data, and gates (a disabled or cut-off node). Whoever brings it to
// zero queues the node: exactly once. A firing reserves, in one step, every condition it
// consumes (its inputs become empty, its receivers get an unread message, its data is used up);
// each is released as it is met again (a message delivered, a message read, notifyNewData).
//
// The structural counts (connected and live inputs, counted outputs) change only in edits,
// with the node's group paused; edits then correct `blockers` by how much its structural part
// changed (EditScope). `blockers` itself is atomic: firings of other groups release it.
#pragma once

#include <atomic>

namespace apex {
namespace detail {

class Readiness {
 public:
  // ---------------------------------------------------------------- structure (edits only)
  /** A data input got a connection, or lost it. */
  void inputConnected() { ++connected_inputs_; }
  void inputDisconnected() { --connected_inputs_; }
  /** A data output got a receiver that counts (not a parameter output), or lost it. */
  void receiverConnected() { ++counted_out_; }
  void receiverDisconnected() { --counted_out_; }
  /** How many connected inputs are fed by a node that can fire (graph_live.cpp). */
  void setLiveInputs(int n) { live_inputs_ = n; }

  int connectedInputs() const { return connected_inputs_; }
  int liveInputs() const { return live_inputs_; }
  int countedReceivers() const { return counted_out_; }

  // ---------------------------------------------------------------- the counter
  /** A new node: a driven source waits for its first notifyNewData(), others for nothing yet
   *  (the edit that adds it counts its structure). */
  void start(bool driven) { blockers_.store(driven ? 1 : 0); }
  /** Nothing keeps the node from firing now. */
  bool ready() const { return blockers_.load(std::memory_order_acquire) == 0; }
  /** An edit changed the structural part by `delta` (EditScope); true if it is zero now. */
  bool correct(int delta) { return blockers_.fetch_add(delta, std::memory_order_acq_rel) + delta == 0; }
  /** More conditions to wait for: `k` receivers of messages a slot handler sent. */
  void block(int k) { blockers_.fetch_add(k, std::memory_order_acq_rel); }
  /** `k` conditions met (a message delivered or read, new data); true if that made it ready:
   *  the caller queues the node. */
  bool release(int k) { return blockers_.fetch_sub(k, std::memory_order_acq_rel) == k; }
  /** A firing reserves what it consumes: every live input, every counted receiver, a driven
   *  source's data. True if it is ready again at once (a release arrived first: see
   *  NodeState::reserve). */
  bool reserve(bool driven) {
    const int k = live_inputs_ + counted_out_ + (driven ? 1 : 0);
    return blockers_.fetch_add(k, std::memory_order_acq_rel) + k == 0;
  }
  /** reserve() for a node that is not driven, without a locked instruction (one per hop less).
   *  Its counter is zero, and nothing but this thread can change it now: every release answers
   *  a condition a firing reserved (none is left at zero), notifyNewData() counts only for a
   *  driven source, and edits pause the group. A release that the firing makes possible (a
   *  receiver reads, a sender delivers) comes after the handoff that this store precedes. */
  void reserveAtZero() { blockers_.store(live_inputs_ + counted_out_, std::memory_order_relaxed); }

 private:
  std::atomic<int> blockers_{0};
  int connected_inputs_ = 0;  // data inputs with an edge
  int live_inputs_ = 0;  // ... whose edge is live
  int counted_out_ = 0;  // counted edges leaving its data outputs
};

}  // namespace detail
}  // namespace apex
