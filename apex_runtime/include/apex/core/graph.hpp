// The graph: nodes, connections, thread groups and every rule about editing
// them. All methods are thread-safe and may be called while the graph runs;
// edits pause only the thread groups of the nodes they touch. They must not be
// called from node code (process() or a slot handler) of the same graph: that
// throws std::logic_error, since the call would wait for its own thread group.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "apex/core/description.hpp"
#include "apex/core/registry.hpp"
#include "apex/core/result.hpp"
#include "apex/core/trace.hpp"

namespace apex {

/** @brief Sees every message sent on one port; runs on the node's thread group, so it must be quick. */
using PortTap = std::function<void(const Message&)>;

/** @brief The node `path` names ("a" or "a/b/c" inside subgraphs), or nullptr. */
const NodeDescription* findNode(const GraphDescription& graph, const std::string& path);

/** @brief What a load reports besides success: e.g. nodes kept as placeholders. */
struct LoadReport {
  std::vector<std::string> warnings;
};

class Graph {
 public:
  explicit Graph(NodeRegistry registry = NodeRegistry::fromGlobal());
  ~Graph();
  Graph(const Graph&) = delete;
  Graph& operator=(const Graph&) = delete;

  const NodeRegistry& registry() const;
  NodeRegistry& registry();
  /** @brief What nodes added from now on see as Node::host(): set it before adding nodes. */
  void setHost(std::shared_ptr<const Host> host);
  /** @brief Whether an edit downstream of a source that holds a frame (a paused player's, or
   *  one at the end of its pass) has the source send that frame again, so the edit shows on it
   *  (Node::downstreamChanged). On by default; off for a graph that replays whole passes (the
   *  Optimizer's copies), where the frame sent again would be counted into the next pass. */
  void setRerunOnEdit(bool on);

  // --- edits: each returns why it was refused; a refused edit changes nothing ---
  /** @brief Adds a node of a registered type. An empty name is generated from the
   *  type; an empty group means "default"; a new group is created. Returns the name. */
  Result<std::string> addNode(const std::string& type, const std::string& name = "", const std::string& thread_group = "");
  /** @brief Adds a node with the settings of a description (parameters, interactive set,
   *  enabled, group, UI), all or nothing: if one setting is refused, no node is added.
   *  A description of type kSubgraphType adds a subgraph: its inner nodes, connections and
   *  exports, then the settings of its exported parameters.
   *
   *  Subgraphs (docs/architecture.md): inner nodes are ordinary nodes of this graph named
   *  "<subgraph>/<node>", addressed so by every call; a subgraph's own name stands for its
   *  exports (connect, setParameter, setInteractive, fireSlot, setTap) and for all of its
   *  nodes (removeNode, setEnabled, setThreadGroup). */
  Result<std::string> addNode(const NodeDescription& description);
  Status removeNode(const std::string& name);
  /** @brief Makes `nodes` (all beside each other: at the top, or in one subgraph) a new
   *  subgraph `name` in their place, as one live edit: nothing is rebuilt, no message is
   *  lost, and every connection crossing its boundary goes through an export named after
   *  the inner port (one export per outside sender it receives from, one per inner sender).
   *  With `restore` (the undo of an ungroup): if these very nodes were last ungrouped from a
   *  subgraph of that name, it comes back as it was — its exports (parameters included), file,
   *  enabled state and position — where its exports still fit; else as without. */
  Status group(const std::vector<std::string>& nodes, const std::string& name, bool restore = false);
  /** @brief The opposite: the subgraph's nodes move up beside where it was, its exports go,
   *  every connection stays. Refused if one of its nodes' names is taken there. */
  Status ungroup(const std::string& name);
  /** @brief Gives a node (or a subgraph, with everything in it) a new name in its place, as one
   *  live edit: its connections, settings and the exports naming it follow; nothing is rebuilt.
   *  `new_name` is a name, not a path: the node stays where it is (group or ungroup to move it). */
  Status rename(const std::string& name, const std::string& new_name);
  /** @brief Connects an output, parameter or trigger to an input, parameter or slot. */
  Status connect(const std::string& from_node, const std::string& from_port, const std::string& to_node,
                 const std::string& to_port);
  /** @brief Removes a connection; a message still pending on it is dropped. */
  Status disconnect(const std::string& from_node, const std::string& from_port, const std::string& to_node,
                    const std::string& to_port);
  /** @brief Sets a parameter from YAML text; returns the applied value as text. */
  Result<std::string> setParameter(const std::string& node, const std::string& param, const std::string& yaml_text);
  /** @brief Gives a parameter an input and an output port, or removes them (and their connections). */
  Status setInteractive(const std::string& node, const std::string& param, bool interactive);
  Status setEnabled(const std::string& node, bool enabled);
  /** @brief Moves a node to a thread group, creating the group if new. */
  Status setThreadGroup(const std::string& node, const std::string& group);
  /** @brief Removes a thread group no node is in (its thread ends): refused for "default" and
   *  for a group with work still posted (a timer or mail a node left there), named. */
  Status removeThreadGroup(const std::string& group);
  /** @brief Sends an event to a node's slot, as if a trigger fired. */
  Status fireSlot(const std::string& node, const std::string& slot);
  /** @brief Stores front-end metadata (YAML flow text, e.g. "{x: 10, y: 20}") with the node. */
  Status setUi(const std::string& node, const std::string& ui_yaml);
  /** @brief Installs (or, with an empty tap, removes) an observer of an output or of an
   *  interactive parameter's output. Costs nothing on ports without one. A held frame (a paused
   *  player's) is sent again, as after an edit, so that a tap installed (or installed again:
   *  someone new watches) on a held graph sees the frame at once. */
  Status setTap(const std::string& node, const std::string& port, PortTap tap);

  // --- running ---
  /** @brief Starts every thread group. Nodes that are ready fire. */
  void start();
  /** @brief Stops and joins every thread group. Idempotent. */
  void stop();
  /** @brief Holds all firing at the next firing boundary (events and edits still apply). */
  void pause();
  void resume();
  bool paused() const;
  /** @brief While paused: fires each node that is ready now, once, and returns when done
   *  (one wave: a frame moves one node further). */
  void step();
  /** @brief While paused: one frame. Every source that is ready fires once, and every node
   *  its data reaches fires until the frame has gone all the way through (sources stay held);
   *  returns when nothing more can fire. Refused while running, or if the frame does not
   *  finish within `timeout_s`. */
  Status stepFrame(double timeout_s = 30.0);

  // --- reading ---
  /** @brief The whole graph as plain data (nodes in insertion order). */
  GraphDescription describe() const;
  /** @brief One node (by its path; not a subgraph's façade) as describe() gives it, without
   *  describing the rest: O(1) in the graph's size. */
  Result<NodeDescription> describeNode(const std::string& name) const;
  /** @brief Every connection between the nodes themselves, by their paths (what a subgraph's
   *  ports stand for, not the ports): the flat graph that runs. */
  std::vector<ConnectionDescription> connections() const;
  /** @brief Replaces the whole graph, all or nothing: on any error the graph is untouched. */
  Result<LoadReport> load(const GraphDescription& description);
  /** @brief Every node's profile and state. A node that has not fired for `stall_after_s`
   *  although data reached something upstream of it since (or that is cut off from every
   *  source) says what it waits for in `waiting_for`; 0 says it for every node. */
  std::vector<NodeStats> nodeStats(double stall_after_s = 1.0) const;
  std::vector<GroupStats> groupStats() const;
  /** @brief A node's histograms of firing time and latency (NodeProfile), over the window of
   *  nodeStats()' percentiles; an error naming the node if there is none such. */
  Result<NodeProfile> nodeProfile(const std::string& node) const;
  /** @brief The frame trace (trace.hpp), off at first: while on, each thread group keeps its last
   *  kTraceFirings firings (node, start, end, frame), written by its own thread without a lock;
   *  turned off, what was kept can still be read. Off, it costs one flag read per run of firings. */
  void setTracing(bool on);
  bool tracing() const;
  /** @brief The firings kept that ended in the last `seconds` (every one kept if `seconds` <= 0),
   *  each group's oldest first, nodes named as they are now. */
  Trace trace(double seconds = 0) const;
  /** @brief A node's type, or nullptr if there is no such node (or it is a placeholder). */
  std::shared_ptr<const NodeType> nodeType(const std::string& node) const;
  /** @brief A node's ports, events and parameters as they are now (its type's manifest, or
   *  what the type's interface function made of it); nullptr if no such node or a placeholder. */
  std::shared_ptr<const Manifest> nodeInterface(const std::string& node) const;
  /** @brief The node object itself (for tests and hosts); nullptr if none. */
  Node* nodeObject(const std::string& node) const;
  std::size_t size() const;
  /** @brief A parameter's current (requested) value. */
  Result<ParamValue> parameterValue(const std::string& node, const std::string& param) const;
  /** @brief Grows with every visible change from any source (edits, parameter values
   *  arriving through ports, errors, enable events): poll it to know when to republish. */
  std::uint64_t revision() const;
  /** @brief Grows with every change of what a save keeps, made from outside a node: edits and
   *  values arriving through parameter inputs, not a node's own reports (a player's frame, an
   *  optimiser's progress): poll it to know the graph was edited. */
  std::uint64_t editRevision() const;

  /** @brief Waits until no node is ready or firing and no event is pending (a stopped
   *  group counts as idle), or the timeout passes; true if idle. For tests and shutdown. */
  bool waitIdle(double timeout_s) const;

 private:
  struct Impl;  // the members and every private step: src/core/graph_impl.hpp
  std::unique_ptr<Impl> impl_;
};

}  // namespace apex
