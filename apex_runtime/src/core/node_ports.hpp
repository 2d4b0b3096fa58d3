// What NodeState is built from, port by port: the connections (Edge, EventEdge), the state of
// each input, output and parameter, and the graph's change counters its nodes share. Who owns
// which field, and under which lock, is at the top of node_state.hpp.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "apex/core/histogram.hpp"
#include "apex/core/message.hpp"
#include "apex/core/param.hpp"

namespace apex {
namespace detail {

class NodeState;

/** Where the registry puts the built-in events (registry.cpp): first in every manifest(). */
constexpr int kEnableIndex = 0, kDisableIndex = 1;  // slots
constexpr int kProcessedIndex = 0;  // trigger

/** A data or parameter connection. `from_param`: from a parameter output;
 *  `to_param`: into a parameter input. */
struct Edge {
  NodeState* from = nullptr;
  bool from_param = false;
  int from_index = 0;
  NodeState* to = nullptr;
  bool to_param = false;
  int to_index = 0;
  std::atomic<bool> unread{false};  // counted edges: the receiver has not taken the last message
  /** From a source that keeps the newest (SourceMode::Newest): read once the receiver's firing
   *  ends, not when it takes the message (set when connected). */
  bool read_after_firing = false;
  bool dead = false;  // removed; pending mail on it is ignored
  bool live = false;  // its sender can fire (edits only): a dead input is treated as Nothing
  /** Data outputs wait for their receivers; parameter outputs never hold a node back. */
  bool counted() const { return !from_param; }
  /** From a parameter output into a parameter: the newest value not yet applied (Nothing when
   *  none). One mail carries it, whatever number of values came meanwhile (NodeState::deliverSlow). */
  Message newest;
  std::mutex newest_m;
};

struct EventEdge {
  NodeState* from = nullptr;
  int trigger = 0;
  NodeState* to = nullptr;
  int slot = 0;
  bool to_source = false;  ///< the receiver has no inputs (when connected): its events go last
  /** Events posted to the receiver and not yet run; beyond kMaxPendingEvents one is dropped
   *  (NodeState::fireTrigger). `dropped` counts them for the warning. */
  std::atomic<int> pending{0};
  std::atomic<long> dropped{0};
};

/** Events one connection may have waiting for a slot that runs slower than its trigger fires
 *  (enable/disable excepted: they set a state): without a bound a fast sender fills the
 *  receiver group's mailbox faster than it empties. */
constexpr int kMaxPendingEvents = 64;

struct InputState {
  Message msg;  // delivered, not yet taken
  std::atomic<bool> full{false};
  std::shared_ptr<Edge> edge;
  Message current;  // taken for this firing
  std::mutex m;  // on the data path only for edges that are not counted; edits take it too (last: cache lines)
};

/** Sees every message of a port (inspection); runs on the node's group thread. */
using Tap = std::function<void(const Message&)>;

/** A count its group thread adds to and any thread reads; copied and moved as a number (an
 *  interface change moves the outputs while their group is paused). */
struct RelaxedCount {
  std::atomic<std::uint64_t> n{0};
  RelaxedCount() = default;
  RelaxedCount(const RelaxedCount& o) : n(o.get()) {}
  RelaxedCount& operator=(const RelaxedCount& o) {
    n.store(o.get(), std::memory_order_relaxed);
    return *this;
  }
  void add() { n.store(n.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed); }  // one writer
  std::uint64_t get() const { return n.load(std::memory_order_relaxed); }
};

/** An output's latency: that of the firings which sent on it (an output that sends on some
 *  frames only has its own), and the readings its window is over (NodeState::shared_'s lock). */
struct OutputLatency {
  Histogram hist;  // group thread adds, any thread reads
  HistogramCounts base, newer;  // NodeState::shared_'s lock: as Shared::window
};

struct OutputState {
  std::vector<std::shared_ptr<Edge>> edges;
  Message pending;
  Tap tap;
  RelaxedCount sent;  // messages sent (not Nothing, not an end of sequence): the rate on its links
  std::uint64_t latency_seen = 0;  // group thread: `sent` when a latency was last counted
  /** Made by the group thread (under NodeState::shared_'s lock) at its first live latency: 6 KiB that an output
   *  without live frames does without. Shared: it moves with its output through an interface change. */
  std::shared_ptr<OutputLatency> latency;
};

struct ParamState {
  ParamValue requested;  // NodeState::shared_'s lock
  ParamValue active;  // group thread
  bool interactive = false;
  bool resend = false;  // NodeState::shared_'s lock: set again (ParamSpec::every_set), apply even if unchanged
  std::shared_ptr<Edge> in_edge;
  std::vector<std::shared_ptr<Edge>> out_edges;
  Tap tap;
};

/** The graph's change counters, shared with its nodes. */
struct Revisions {
  /** Every change a client shows: edits, and a node's own reports (a player's frame), errors,
   *  enabling, pausing. */
  std::atomic<std::uint64_t> visible{0};
  /** What a save keeps, changed from outside the node: edits, and values arriving through
   *  parameter inputs. Not a node's own reports: a playing bag is not an unsaved change. */
  std::atomic<std::uint64_t> edited{0};
  void shown() { visible.fetch_add(1, std::memory_order_relaxed); }
  void edit() {
    edited.fetch_add(1, std::memory_order_relaxed);
    shown();
  }
};

}  // namespace detail
}  // namespace apex
