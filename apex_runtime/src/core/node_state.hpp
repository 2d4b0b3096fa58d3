// The runtime side of one node: its ports, connections, parameters and the
// counter that decides when it may fire.
//
// Who owns what:
//  - Structure (edges, counts, group, interactive flags) changes only in Graph
//    edits, under Graph::edit_mutex_, while every thread group that could touch
//    the node is paused.
//  - Firing state (current inputs, pending outputs, active parameters,
//    active_enabled) belongs to the node's group thread.
//  - An input slot (msg, full) is the one handoff between threads: its mutex.
//  - `blockers` counts what keeps the node from firing: empty connected inputs,
//    receivers that have not read its last message, and gates. Whoever brings
//    it to zero pushes the node onto its group's ready queue: exactly once.
//  - state_mutex guards what other threads read: requested parameter values,
//    the error text, the enabled flag, UI metadata.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "apex/core/description.hpp"
#include "apex/core/registry.hpp"
#include "thread_group.hpp"

namespace apex {
namespace detail {

class NodeState;

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
  bool dead = false;                // removed; pending mail on it is ignored
  /** Data outputs wait for their receivers; parameter outputs never hold a node back. */
  bool counted() const { return !from_param; }
};

struct EventEdge {
  NodeState* from = nullptr;
  int trigger = 0;
  NodeState* to = nullptr;
  int slot = 0;
};

struct InputState {
  std::mutex m;
  Message msg;  // delivered, not yet taken
  bool full = false;
  std::shared_ptr<Edge> edge;
  Message current;  // taken for this firing
};

/** Sees every message of a port (inspection); runs on the node's group thread. */
using Tap = std::function<void(const Message&)>;

struct OutputState {
  std::vector<std::shared_ptr<Edge>> edges;
  Message pending;
  Tap tap;
};

struct ParamState {
  ParamValue requested;  // state_mutex
  ParamValue active;     // group thread
  bool interactive = false;
  std::shared_ptr<Edge> in_edge;
  std::vector<std::shared_ptr<Edge>> out_edges;
  Tap tap;
};

class NodeState : public std::enable_shared_from_this<NodeState> {
 public:
  NodeState(std::string name, std::shared_ptr<const NodeType> type, std::uint64_t seq,
            std::shared_ptr<std::atomic<std::uint64_t>> revision);
  ~NodeState();

  const std::string name;
  const std::shared_ptr<const NodeType> type;  // nullptr: placeholder
  const Manifest& manifest;
  const std::uint64_t seq;
  std::shared_ptr<std::atomic<std::uint64_t>> revision;  // the graph's: bumped on every visible change
  std::unique_ptr<Node> node;
  void attach(std::unique_ptr<Node> object) {
    node = std::move(object);
    node->state_.store(this, std::memory_order_release);
  }

  std::vector<std::unique_ptr<InputState>> inputs;
  std::vector<OutputState> outputs;
  std::vector<ParamState> params;
  std::vector<std::vector<std::shared_ptr<EventEdge>>> trigger_edges;  // per trigger
  std::vector<std::vector<std::shared_ptr<EventEdge>>> slot_edges;     // per slot, incoming
  int connected_inputs = 0;
  int counted_out = 0;

  // scheduling
  std::atomic<int> blockers{0};
  bool queued = false;  // group mutex
  std::atomic<bool> has_data{false};
  ThreadGroup* group = nullptr;
  std::mutex group_mutex;  // for readers of `group` outside edits (notifyNewData)
  bool removed = false;

  // shared with other threads
  mutable std::mutex state_mutex;
  bool enabled = true;  // requested
  std::string ui;
  NodeDescription placeholder;  // for placeholders: the description, kept verbatim
  std::string error() const;

  // --- group thread ---
  /** Fires if nothing blocks it (an edit may have blocked it since it was queued). */
  bool fireIfReady();
  void recordFiring(std::int64_t ns);
  void applyParams();
  /** Node::setup(), once; a throw is the node's error. */
  void runSetup();
  void applyEnabled();
  void runSlot(int slot);
  void receiveParam(Edge& edge, const Message& m);
  void fireTrigger(int trigger);
  void setOutput(int index, Message m);

  // --- any thread ---
  void unblock(int k);
  void post(std::function<void(NodeState&)> fn);
  void notifyNewData();
  void notifyAfter(double seconds);
  /** Requested value changed: apply on the group thread before the next firing. */
  void requestParam(int index, ParamValue v);

  // --- edits (groups paused) ---
  /** The part of `blockers` that only edits and firings change (not has_data). */
  int structuralBlockers();
  bool driven() const { return manifest.source_mode == SourceMode::Driven; }
  NodeStats stats() const;

  int findInput(const std::string& n) const;
  int findOutput(const std::string& n) const;
  int findParam(const std::string& n) const;
  int findTrigger(const std::string& n) const;
  std::string typeId() const { return type ? type->id : placeholder.type; }

 private:
  int gates() const;
  void adjust(int delta);
  void deliver(const std::shared_ptr<Edge>& edge, const Message& m);
  void publishParam(int index);
  void setError(std::string text);
  void clearError();

  bool active_enabled_ = true;
  std::atomic<bool> params_dirty_{false};
  bool apply_posted_ = false;  // state_mutex
  std::atomic<bool> has_error_{false};
  std::string error_;  // state_mutex
  std::chrono::steady_clock::time_point error_logged_;  // state_mutex
  static constexpr std::chrono::seconds kErrorLogInterval{5};
  std::atomic<std::uint64_t> firings_{0}, last_ns_{0}, total_ns_{0}, max_ns_{0};
};

}  // namespace detail
}  // namespace apex
