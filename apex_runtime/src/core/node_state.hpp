// The runtime side of one node: its ports, connections, parameters and the
// counter that decides when it may fire.
//
// Who owns what (every field is private, and NodeState has no friends: everyone, graph code
// too, goes through the operations below; the owner of each field is in its section):
//  - Structure (edges, counts, group, name, interface, live, removed, interactive flags)
//    changes only in Graph edits, under Graph::edit_mutex_, while every thread group that
//    could touch the node is paused: link/unlink, moveTo, markRemoved, setInterface,
//    updateLive, rename... Edits and the group thread read it through the const calls
//    (inputEdge, outputEdges, ...) and walk it with forEachNeighbour / forEachDataReceiver /
//    forEachSender.
//  - Firing state (current inputs, pending outputs, active parameters,
//    active_enabled) belongs to the node's group thread.
//  - Its queue mark (queued, from outside, ready mark) belongs to its ThreadGroup, under
//    the group's mutex: markQueued / clearQueued.
//  - An input slot (msg, full) is the one handoff between threads. On a counted
//    edge the firing rule itself makes it exclusive (the sender writes only once
//    the receiver took the last message; the receiver takes only when full), so
//    the `blockers` atomics order it; an uncounted edge (from a parameter output,
//    which overwrites) uses the slot's mutex.
//  - the blockers (readiness.hpp) count what keeps the node from firing: empty live inputs,
//    receivers that have not read its last message, and gates. Whoever brings
//    it to zero pushes the node onto its group's ready queue: exactly once.
//  - Liveness (`live_`, `Edge::live`, Readiness::liveInputs) is structure: only edits
//    change it (graph_live.cpp), with the groups of every node it touches paused.
//  - Shared (the enabled flags, UI metadata, the error text, the stats window) is behind
//    a Guarded: reached only through the handle shared_.lock() returns, which holds its
//    mutex. That lock also covers requested parameter values (ParamState::requested) and a
//    swap of the ports on an interface change, which other nodes' threads read under it.
//  - Atomics (has_data_, counters, dropped_) may be read and written anywhere.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "apex/core/description.hpp"
#include "apex/core/histogram.hpp"
#include "apex/core/node_names.hpp"
#include "apex/core/registry.hpp"
#include "guarded.hpp"
#include "node_ports.hpp"
#include "readiness.hpp"
#include "thread_group.hpp"
#include "ticks.hpp"

namespace apex {
namespace detail {

class EditRequests;

class NodeState : public std::enable_shared_from_this<NodeState> {
 public:
  NodeState(std::string name, std::shared_ptr<const NodeType> type, std::uint64_t seq, std::shared_ptr<Revisions> revisions);
  ~NodeState();

  /** Its path in the graph. Changed only by group/ungroup (Graph::moveLocked), with its
   *  group and its neighbours' paused: node code reads it on its own thread group. */
  const std::string& name() const { return name_; }
  /** Its place in the graph's insertion order; names it in traces. */
  std::uint64_t seq() const { return seq_; }
  const Manifest& manifest() const { return *iface_; }
  std::string typeId() const { return type_ ? type_->id : placeholder_.type; }
  /** The graph's host when the node was made (Node::host); may be null. */
  const Host* host() const { return host_.get(); }
  /** Its thread group: set by edits (groups paused), read by its group thread and edits. */
  ThreadGroup* group() const { return group_; }
  /** Its group, read under group_mutex_ against a move, from any thread; nullptr once it is
   *  removed (ThreadGroup::runMail: its mail follows it or is dropped). */
  ThreadGroup* homeGroup() {
    std::lock_guard<std::mutex> lock(group_mutex_);
    return removed_ ? nullptr : group_;
  }
  void attach(std::unique_ptr<Node> object);
  /** A source by structure: no data input connected, and none mandatory. */
  bool isSource() const;

  // --- structure walks (edits, or the node's group thread) ---
  /** f(NodeState*) for each node at the other end of a data or parameter connection. */
  template <class F>
  void forEachDataOrParamNeighbour(F&& f) const;
  /** ... and of an event connection too. */
  template <class F>
  void forEachNeighbour(F&& f) const;
  /** f(Edge&) for each edge from an output or a parameter output into a data input. */
  template <class F>
  void forEachDataReceiver(F&& f) const;
  /** f(const std::shared_ptr<Edge>&) for the edge into each data and parameter input (null if none). */
  template <class F>
  void forEachSender(F&& f) const;
  std::size_t inputCount() const { return inputs_.size(); }
  std::size_t outputCount() const { return outputs_.size(); }
  /** A node of a type not loaded: it keeps its description and never fires. */
  bool isPlaceholder() const { return !type_; }
  /** Its type (null for a placeholder), its interface, its node object (null for a placeholder). */
  const std::shared_ptr<const NodeType>& type() const { return type_; }
  const std::shared_ptr<const Manifest>& iface() const { return iface_; }
  Node* object() const { return node_.get(); }
  /** Whether a source reaches it (structure: edits, or its group thread). */
  bool live() const { return live_; }
  /** Taken out of the graph (Graph::retire): it never fires again, its mail is dropped. */
  bool removed() const { return removed_; }
  /** Marks it removed, under group_mutex_ against a thread that posts to it (homeGroup). */
  void markRemoved();
  /** Puts it in group `g` (an edit, both groups paused), off its old group's queue. Under
   *  group_mutex_ throughout: a notifyNewData() sees the old group with the node unqueued from
   *  it, or the new one; it never queues it on the old one afterwards. */
  void moveTo(ThreadGroup* g);
  /** Joins a graph: where Node::requestEdit asks, the change counters, the host (new or adopted
   *  nodes, before any thread reaches them). */
  void joinGraph(std::shared_ptr<Revisions> revisions, std::shared_ptr<EditRequests> edits);
  void setHost(std::shared_ptr<const Host> host) { host_ = std::move(host); }
  /** A placeholder's description, kept verbatim (a new placeholder, before it joins a group). */
  void setPlaceholder(NodeDescription d) { placeholder_ = std::move(d); }
  /** Nothing keeps it from firing now (readiness.hpp). */
  bool ready() const { return readiness_.ready(); }
  /** Whether parameter `p` has its input and output ports. */
  bool interactive(int p) const { return params_[p].interactive; }
  /** The edge into data input `i` or parameter `p` (null if none), and those out of output `i`,
   *  parameter output `p`, trigger `t`, and into slot `s`. */
  const std::shared_ptr<Edge>& inputEdge(int i) const { return inputs_[i]->edge; }
  const std::shared_ptr<Edge>& paramInEdge(int p) const { return params_[p].in_edge; }
  const std::vector<std::shared_ptr<Edge>>& outputEdges(int i) const { return outputs_[i].edges; }
  const std::vector<std::shared_ptr<Edge>>& paramOutEdges(int p) const { return params_[p].out_edges; }
  const std::vector<std::shared_ptr<EventEdge>>& triggerEdges(int t) const { return trigger_edges_[t]; }
  const std::vector<std::shared_ptr<EventEdge>>& slotEdges(int s) const { return slot_edges_[s]; }
  /** Its description as a save keeps it (under shared_'s lock: requested values, enabled, ui). */
  NodeDescription describe() const;
  // --- connections (edits, the groups of both ends paused; graph_connect.cpp) ---
  /** Puts `e` at both its ends (Edge::from's output or parameter output, Edge::to's input or
   *  parameter) and counts it in their readiness. */
  static void link(const std::shared_ptr<Edge>& e);
  /** Sees every message of output `i`, or every value of parameter `p` (its group paused). */
  void setOutputTap(int i, Tap tap) { outputs_[i].tap = std::move(tap); }
  void setParamTap(int p, Tap tap) { params_[p].tap = std::move(tap); }
  /** Whether parameter `p` has ports (an edit: the caller has removed its connections first). */
  void setInteractive(int p, bool on) { params_[p].interactive = on; }
  /** Its new path (group/ungroup: Graph::moveLocked, with its group and neighbours' paused). */
  void rename(std::string path) { name_ = std::move(path); }
  /** Takes `e` off both its ends; a message waiting at a data input is dropped with it. */
  static void unlink(const std::shared_ptr<Edge>& e);
  static void link(const std::shared_ptr<EventEdge>& e);
  /** False if it was not linked (taken off already). */
  static bool unlink(const std::shared_ptr<EventEdge>& e);
  /** Every data or parameter connection at any of its ports, and every event connection. */
  std::vector<std::shared_ptr<Edge>> edges() const;
  std::vector<std::shared_ptr<EventEdge>> events() const;
  /** Recomputes `live_` from its senders' (graph_live.cpp walks the region in topological order). */
  void updateLive();
  /** A new node with no connection yet: live if it is a source. */
  void initLive() { live_ = type_ && isSource(); }
  /** An edit changed its structural blockers by `delta` (EditScope); queues it if that left it
   *  ready (push is idempotent: a ready node moved or taken off a queue is queued again). */
  void correctBlockers(int delta);

  // --- its group's queue: ThreadGroup's, under the group's mutex ---
  bool queued() const { return queued_; }
  /** Marks it queued behind `mail_sent` mails of its group; false if it already was. */
  bool markQueued(std::uint64_t mail_sent) {
    if (queued_) return false;
    queued_ = true;
    ready_mark_ = mail_sent;
    return true;
  }
  /** ... by push(), from outside its group's own firing. */
  void markFromOutside() { queued_from_outside_ = true; }
  /** Off the queue; true if it was queued from outside (the group counts those). */
  bool clearQueued() {
    const bool outside = queued_from_outside_;
    queued_ = queued_from_outside_ = false;
    return outside;
  }
  /** How much mail its group had been sent when it was queued. */
  std::uint64_t readyMark() const { return ready_mark_; }

  // --- what node code (apex::Node) reaches, on the group thread ---
  const Message& currentInput(int index) const { return inputs_[index]->current; }
  Message takeInput(int index) { return std::move(inputs_[index]->current); }
  const ParamValue& activeParam(int index) const { return params_[index].active; }
  /** Node::countDropped, from any thread. */
  void countDropped(std::uint64_t n) { dropped_.fetch_add(n, std::memory_order_relaxed); }
  /** Where Node::requestEdit asks (the graph's); null outside a graph. */
  EditRequests* editRequests() const { return edits_.get(); }

  // --- Shared, and requested parameter values: any thread; each takes shared_'s lock ---
  std::string error() const;
  /** The requested enabled flag (an edit; a placeholder keeps it in its description). Its group
   *  thread applies it (applyEnabled). */
  void setEnabled(bool on);
  /** Whether every subgraph it lies in is enabled (an edit); applied as setEnabled is. */
  void setOuterEnabled(bool on);
  /** Its UI metadata (YAML text the graph keeps for a front end). */
  std::string ui() const;
  void setUi(std::string text);
  /** The value last asked for parameter `index` (setParameter): what a reader and a save see. */
  ParamValue requestedParam(int index) const;
  /** Every parameter's requested value, by name (an interface function's input). */
  ParamValues requestedParams() const;
  /** A parameter of a node not yet in a graph (no thread reads it yet): applied at setup. */
  void presetParam(int index, ParamValue v);

  // --- group thread ---
  /** Fires if nothing blocks it (an edit may have blocked it since it was queued). */
  bool fireIfReady();
  /** Whether the next firing should be timed: the first, every one of a node that took at least
   *  kSlowTicks, else one in kTimeEvery (a clock read costs ~10 ns here, a trivial hop ~40). */
  bool timeNext() const { return untimed_left_ == 0; }
  /** The frame its last firing took in or, for a source, sent (Message::frame); 0 if unknown. */
  std::int64_t frame() const { return frame_; }
  /** Whether its last firing began a frame (took none in, sent a stamped message): a source's. */
  bool startsFrame() const { return starts_frame_; }
  /** Names the frame of each message about to leave (Message::frame): `taken`, the newest frame the
   *  firing took in, or if none (a source) the stamp of its first message that has one. */
  inline void nameFrames(std::int64_t taken);  // node_state_inline.hpp: every firing
  /** A firing took `t` ticks (if `timed`) and ended at tick `end` (if untimed: the group's
   *  newest clock read, a little earlier); one that only passed Nothing is counted apart. */
  inline void recordFiring(bool timed, std::int64_t t, std::int64_t end);  // node_state_inline.hpp: every firing
  void applyParams();
  /** Node::setup(), once; a throw is the node's error. */
  void runSetup();
  void applyEnabled();
  /** A slot's error (the Optimizer's start without a range) stays until a slot runs fine: a data
   *  firing between says nothing about it, and would take it away before anyone saw it. */
  void runSlot(int slot);
  /** Runs `fn` as a slot handler runs: what it publishes leaves when it returns, then its
   *  events; a throw is the node's error, named by `what` (Node::runLater). False if it failed. */
  bool runHandler(const std::string& what, const std::function<void()>& fn);
  /** Node::downstreamChanged(); a throw is the node's error. */
  void runDownstreamChanged();
  /** Applies a value that came into a parameter (on its group's thread); `counted`: the mail that
   *  releases the sender (a slot's value sent behind an unread one is not). */
  void receiveParam(Edge& edge, const Message& m, bool counted = true);
  /** The node set its own parameter (Node::updateParam); a pending request stays and wins. */
  void updateParam(int index, ParamValue v);
  /** Sends an event; from process() or a slot handler it waits until the messages published
   *  there have left (releaseTriggers), so a receiver of both sees the data first. */
  void fireTrigger(int trigger);
  void setOutput(int index, Message m) { outputs_[index].pending = std::move(m); }
  /** Node::reportError: the node's error, kept past the end of this firing. */
  void reportError(const std::string& text);
  /** The parameter inputs output `index` feeds (Node::parameterTargets). */
  std::vector<ParamTarget> parameterTargets(int index) const;

  // --- any thread ---
  /** Releases k blockers; at zero the node is queued. `here`: the group whose thread is
   *  firing now (nullptr elsewhere); a node of that group then runs next on it. */
  void unblock(int k, ThreadGroup* here = nullptr) {  // inline: twice per hop
    if (!readiness_.release(k)) return;
    if (here != nullptr && here == group_) {
      here->runNext(this);  // made ready by a firing on its own group's thread: runs next, no queue
    } else {
      group_->push(this);
    }
  }
  void post(std::function<void(NodeState&)> fn);
  /** post() from any thread, at any time (Node::runLater): nothing once the node is being
   *  destroyed; skipped by its group once it is removed. */
  void postFromAnywhere(std::function<void(NodeState&)> fn);
  void notifyNewData();
  void notifyAfter(double seconds);
  /** Something downstream changed (an edit): Node::downstreamChanged() on the group thread now,
   *  or, within `interval` of the last call, once at the end of that interval: a burst of
   *  changes gives one run per interval and always one after the last change. */
  void downstreamChanged(std::chrono::steady_clock::duration interval);
  /** Requested value changed: apply on the group thread before the next firing. */
  void requestParam(int index, ParamValue v);

  // --- edits (groups paused) ---
  /** The part of the blockers that only edits and firings change (not has_data_). */
  int structuralBlockers();
  bool driven() const { return driven_; }
  /** Its receivers read its messages when their firing ends (SourceMode::Newest). */
  bool sendsNewest() const { return iface_->source_mode == SourceMode::Newest; }
  NodeStats stats() const;
  /** Its mean firing time, ns (0 before a timed firing): cheap, any thread, moves no window. */
  std::uint64_t meanNs() const;
  /** Its histograms over the window stats() keeps (NodeProfile). */
  NodeProfile profile() const;
  /** When the node last fired, or was made if never (ticks.hpp). */
  std::int64_t lastFired() const { return last_fired_.load(std::memory_order_relaxed); }
  /** When its last firing that took or sent data began, in ticks (0: none yet; untimed: a
   *  clock read a little before). */
  std::int64_t lastSent() const { return last_sent_.load(std::memory_order_relaxed); }
  /** What keeps it from firing now, as a sentence ("" if nothing). Any thread. */
  std::string waitingFor() const;
  /** Drops every message on its inputs and every unread mark on its outputs (groups paused). */
  void flushPorts();

  /** Replaces the interface, keeping the state of every port whose name and kind stay and
   *  re-indexing its edges; the caller has removed the edges of the others (graph_interface.cpp). */
  void setInterface(std::shared_ptr<const Manifest> next);

  int findInput(std::string_view n) const;
  int findOutput(std::string_view n) const;
  int findParam(std::string_view n) const;
  int findTrigger(std::string_view n) const;

 private:
  // No friends: graph code, too, goes through the operations above. NodeState's own members
  // that belong to an edit are defined beside it: link/unlink in graph_connect.cpp,
  // setInterface in graph_interface.cpp, describe in graph_load.cpp.

  // Hot first: what a firing reads, in the order it reads it (see "Cold and large" below).
  // --- structure (edits only, groups paused; its group thread reads) ---
  std::string name_;
  const std::shared_ptr<const NodeType> type_;  // nullptr: placeholder
  /** The instance's interface: its type's manifest, or what Manifest::shape made of it.
   *  Replaced by edits only (graph_interface.cpp), with the node's group paused. */
  std::shared_ptr<const Manifest> iface_;
  const std::uint64_t seq_;
  std::shared_ptr<Revisions> revisions_;  // the graph's
  std::unique_ptr<Node> node_;  // made once (attach), before it joins a group

  // Ports: their edges are structure; a port's firing state (InputState::current,
  // OutputState::pending, ParamState::active) is its group thread's; ParamState::requested is
  // under shared_'s lock; InputState::msg/full is the one handoff (see the top of this file).
  std::vector<std::unique_ptr<InputState>> inputs_;
  std::vector<OutputState> outputs_;
  std::vector<ParamState> params_;
  std::vector<std::vector<std::shared_ptr<EventEdge>>> trigger_edges_;  // per trigger
  /** Can fire at all (edits only): a source, or fed by a live input. A node cut
   *  off from every source never fires and holds no other path hostage. */
  bool live_ = false;

  // --- scheduling ---
  Readiness readiness_;  // the firing rule's counters (readiness.hpp): atomic, named transitions
  // Its place in its group's ready queue: ThreadGroup's, under the group's mutex, through
  // markQueued/clearQueued only. (Three fields, not a struct: one would be 8-aligned and move
  // everything after it by 8 bytes.)
  bool queued_ = false;
  bool queued_from_outside_ = false;  // by push(), not by this group's own firing
  std::uint64_t ready_mark_ = 0;  // how much mail its group had been sent when it was queued
  std::atomic<bool> has_data_{false};  // any thread: a driven source's new data (notifyNewData)
  ThreadGroup* group_ = nullptr;  // structure; also read under group_mutex_ (homeGroup)
  bool removed_ = false;  // structure; also read under group_mutex_

  // host_, edits_, slot_edges_, group_mutex_, shared_, placeholder_: declared last (cache lines)

  int gates() const;
  void adjust(int delta);
  void deliver(const std::shared_ptr<Edge>& edge, Message m, ThreadGroup* here = nullptr);
  inline void deliverTo(const std::shared_ptr<Edge>& edge, Message&& m, ThreadGroup* here);  // deliver's body
  /** deliver() to a parameter input or on an edge that is not counted. */
  void deliverSlow(const std::shared_ptr<Edge>& edge, Message&& m, ThreadGroup* here);
  void publishParam(int index, ThreadGroup* here = nullptr);
  void setError(std::string text);
  void clearError();
  /** Runs node code (process(), endOfSequence(), a slot); a throw becomes the node's error,
   *  "node 'n' (type) <what> threw: ...". False if it threw. */
  template <class F>
  bool guarded(const char* what, F&& fn);
  /** Sends what a slot handler published, where every receiver has read the last message;
   *  false if something was refused (the node reports it). */
  bool sendFromSlot(const std::string& slot);
  void releaseTriggers();
  bool in_handler_ = false;  // group thread: process() or a slot handler runs
  bool reported_ = false;  // group thread: reportError() in this firing
  bool slot_error_ = false;  // group thread: the error shown came from a slot, not a firing
  std::vector<int> held_triggers_;  // group thread: fired there, sent after its messages

  const bool driven_;  // the type's source mode: an interface keeps it
  bool active_enabled_ = true;
  std::atomic<bool> params_dirty_{false};
  std::atomic<bool> has_error_{false};
  static constexpr std::chrono::seconds kErrorLogInterval{5};
  // written by the group thread only (load + store, no read-modify-write), read by anyone
  std::atomic<std::uint64_t> firings_{0}, nothing_firings_{0}, timed_firings_{0};
  bool last_had_data_ = false;  // group thread: the firing recorded next moved a message
  std::int64_t frame_ = 0;  // group thread: the frame of the firing recorded next (Message::frame)
  bool starts_frame_ = false;  // group thread: ... which that firing began
  void recordTimedOrNothing(bool timed, std::int64_t t);  // recordFiring's other cases
  std::uint8_t untimed_left_ = 0;  // group thread: firings before the next timed one
  static constexpr int kTimeEvery = 8;
  static constexpr std::int64_t kSlowTicks = 4096;  // ~1-4 µs at a TSC of 1-4 GHz (ticks.hpp)
  std::atomic<std::int64_t> last_t_{0}, total_t_{0}, max_t_{0}, last_fired_{0}, last_sent_{0};  // in ticks (ticks.hpp)
  inline void take(InputState& in, bool optional, bool& skip, bool& read_later);
  /** The firing has ended: the edges of its inputs read only now (Edge::read_after_firing). */
  void readAfterFiring();
  // fireIfReady's steps, in order
  struct Firing {
    bool skip = false;  // disabled, or a mandatory input holds Nothing: process() is not run
    bool end = false;  // an input holds the end of a sequence
    bool data = false;  // an input holds a frame (not Nothing, not the end token): for rates
    bool read_later = false;  // an input's edge is read when the firing ends (Edge::read_after_firing)
    std::int64_t frame = 0;  // the newest frame its inputs belong to (Message::frame)
  };
  inline void reserve();
  inline Firing takeInputs();
  inline void run(const Firing& f);
  /** `data`: the firing consumed a frame; with what it sends, that is last_had_data_. Names
   *  each message's frame (Message::frame) from its payload or from `f.frame`. */
  inline void deliverOutputs(const Firing& f);

  // Cold and large: after everything a firing reads, so that fits in fewer cache lines
  // (with these in the middle, a hop in a chain of 64 relays cost ~2 ns more, measured).
  std::shared_ptr<const Host> host_;  // structure: the graph's, when the node was made
  std::shared_ptr<EditRequests> edits_;  // structure: the graph's, where Node::requestEdit asks
  std::vector<std::vector<std::shared_ptr<EventEdge>>> slot_edges_;  // structure: per slot, incoming
  mutable std::mutex group_mutex_;  // for readers of `group_` outside edits (notifyNewData)
  struct Reading {
    HistogramCounts time, latency;
    std::int64_t latency_total = 0;
    std::uint64_t latency_count = 0;
    std::chrono::steady_clock::time_point at{};
  };
  /** What other threads read and edits set: reached only with its lock held (Guarded). */
  struct Shared {
    bool enabled = true;  // requested
    bool outer_enabled = true;  // every subgraph it lies in is enabled (edits only)
    bool apply_posted = false;  // applyParams() is in its group's mail
    bool resend_due = false;  // a downstreamChanged() is set on a timer
    std::string ui;  // UI metadata
    std::string error;
    std::chrono::steady_clock::time_point error_logged, last_resend;
    /** The older and the newer reading the stats window is over (stats() moves it). */
    mutable std::array<Reading, 2> window;
  };
  Guarded<Shared> shared_;
  NodeDescription placeholder_;  // structure: for placeholders, the description kept verbatim

  const std::chrono::steady_clock::time_point added_at_ = std::chrono::steady_clock::now();  // what profile() is over at first
  // The distributions: written by the group thread (timed firings), read by stats(). The window
  // is the counts since `Shared::window[0]`, a reading 5 to 10 s old.
  Histogram time_hist_, latency_hist_;
  std::atomic<std::int64_t> latency_total_{0};
  std::atomic<std::uint64_t> dropped_{0};  // Node::countDropped, from any thread
  std::atomic<std::uint64_t> latency_count_{0};
  /** A firing with a frame from now: its latency (Message::frame to `wall_ns`) counted. */
  void recordLatency(std::int64_t wall_ns);
  /** Fills the percentiles over `window` (Shared's, with its lock held), moving it on. */
  void fillDistributions(NodeStats& s, std::array<Reading, 2>& window) const;
  static constexpr std::chrono::seconds kWindowStep{5};
  static constexpr std::int64_t kLiveFrameNs = 3600LL * 1000000000LL;  // a frame an hour old is no live one
};

template <class F>
void NodeState::forEachDataOrParamNeighbour(F&& f) const {
  for (auto& in : inputs_)
    if (in->edge) f(in->edge->from);
  for (auto& o : outputs_)
    for (auto& e : o.edges) f(e->to);
  for (auto& p : params_) {
    if (p.in_edge) f(p.in_edge->from);
    for (auto& e : p.out_edges) f(e->to);
  }
}

template <class F>
void NodeState::forEachNeighbour(F&& f) const {
  forEachDataOrParamNeighbour(f);
  for (auto& t : trigger_edges_)
    for (auto& e : t) f(e->to);
  for (auto& s : slot_edges_)
    for (auto& e : s) f(e->from);
}

template <class F>
void NodeState::forEachDataReceiver(F&& f) const {
  for (auto& o : outputs_)
    for (auto& e : o.edges)
      if (!e->to_param) f(*e);
  for (auto& p : params_)
    for (auto& e : p.out_edges)
      if (!e->to_param) f(*e);
}

template <class F>
void NodeState::forEachSender(F&& f) const {
  for (auto& in : inputs_) f(in->edge);
  for (auto& p : params_) f(p.in_edge);
}

template <class F>
inline bool NodeState::guarded(const char* what, F&& fn) {
  auto where = [&] { return nodeLabel(name_, type_->id) + (*what ? std::string(" ") + what : std::string()); };
  try {
    fn();
    return true;
  } catch (const std::exception& ex) {
    setError(where() + " threw: " + ex.what());
  } catch (...) {
    setError(where() + " threw an exception that is not a std::exception");
  }
  return false;
}

}  // namespace detail
}  // namespace apex

#include "node_state_inline.hpp"  // the firing path's inline members that are not in the class
