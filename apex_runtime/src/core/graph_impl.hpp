// What apex::Graph holds (graph.hpp keeps only a pointer to it): the graph's members and
// every step of an edit. Graph's public calls are written once, as Graph's own methods (each
// reads this as `impl`), in graph.cpp (nodes and their settings), graph_connect.cpp,
// graph_load.cpp, graph_run.cpp, graph_subgraph.cpp and graph_trace.cpp; only those that other
// steps use too (a load adds nodes, a group sets parameters) are steps here, which Graph's
// methods call (graph_api.cpp). Subgraph records and their rules are detail::Subgraphs (subgraph.hpp).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "apex/core/graph.hpp"
#include "subgraph.hpp"

namespace apex {

namespace detail {
class NodeState;
class ThreadGroup;
struct Edge;
struct EventEdge;
class Restructure;
class EditRequests;
}  // namespace detail

struct Graph::Impl {
  explicit Impl(NodeRegistry registry);
  ~Impl();  // stops, then retires every node
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  // --- Graph's public calls that other steps use too (a load, a group); Graph's forward here ---
  Result<std::string> addNode(const std::string& type, const std::string& name, const std::string& thread_group);
  Result<std::string> addNode(const NodeDescription& description);
  Status removeNode(const std::string& name);
  Result<std::string> setParameter(const std::string& node, const std::string& param, const std::string& yaml_text);
  Status setInteractive(const std::string& node, const std::string& param, bool interactive);
  Status setEnabled(const std::string& node, bool enabled);
  Status fireSlot(const std::string& node, const std::string& slot);
  Status setUi(const std::string& node, const std::string& ui_yaml);
  void stop();
  /** The description, and a maker of empty graphs with these node types and host. */
  GraphSnapshot snapshot() const;

  // --- the steps ---
  using NodePtr = std::shared_ptr<detail::NodeState>;
  /** Takes the edit mutex; throws std::logic_error when called from this graph's
   *  own node code, where waiting for the node's thread group would deadlock. */
  std::unique_lock<std::mutex> lockEdits() const;
  /** Every group idle (nothing ready that may fire, running or posted), twice in a row. */
  static bool allIdle(const std::vector<std::shared_ptr<detail::ThreadGroup>>& groups, double timeout_s);
  NodePtr find(const std::string& name) const;
  Result<NodePtr> require(const std::string& name) const;
  detail::ThreadGroup* group(const std::string& name);  // creates
  /** OK if `group_name` exists or one more group stays within kMaxGraphGroups; `extra_nodes`
   *  more nodes within kMaxGraphNodes (limits.hpp: what a file may hold). */
  Status roomFor(const std::string& group_name, std::size_t extra_nodes = 0) const;
  /** Connections in the whole graph: data, parameter and event links, and placeholders'. */
  std::size_t connectionCount() const;
  Result<std::string> addPlaceholder(const NodeDescription& d);
  // --- subgraphs (graph_subgraph.cpp; the records alone: subgraphs_) ---
  /** "" if `path` may name a new node or subgraph: free, each part a name, its parent a subgraph. */
  std::string checkNewPath(const std::string& path) const { return subgraphs_.checkNewPath(path, nodes_.count(path) > 0); }
  Result<std::string> addSubgraph(const NodeDescription& d);
  Status checkExports(const detail::Subgraph& sg) const;
  std::vector<std::string> nodesUnder(const std::string& path) const;  // every node inside, nested too
  void removeSubgraphLocked(const std::string& path);
  /** Renames a node or a subgraph and everything in it (`from` and `to` are paths). */
  void moveLocked(const std::string& from, const std::string& to);
  void applyOuterEnabled(const std::string& path);
  std::shared_ptr<const Manifest> facade(const detail::Subgraph& sg) const;
  GraphDescription describeLocked() const;
  /** Connects what the two ends stand for (through subgraph exports), all or nothing. */
  Status connectLocked(const ConnectionDescription& c);
  Status connectDirect(const ConnectionDescription& c);
  Status disconnectDirect(const ConnectionDescription& c);
  Status applyNode(const NodeDescription& d, LoadReport& report);
  void adoptLocked(Impl& staged, const GraphDescription& description);
  void clearLocked();
  void detachAll(detail::NodeState* node);
  /** Disconnects a node and takes it off its group's queue; it never fires again.
   *  `restructure`: keep the rest of the graph consistent (false when all nodes go). */
  void retire(detail::NodeState* node, bool restructure = true);
  static std::vector<detail::NodeState*> dataReceivers(detail::NodeState* node);
  /** The edit of one data or parameter connection between two nodes (see live.hpp). */
  detail::Restructure restructure(detail::NodeState* from, detail::NodeState* to, bool into_data_input) const;
  void removeEdge(std::shared_ptr<detail::Edge> edge);
  /** Tells every source upstream of `node` (and `node` too if `itself`) that something downstream
   *  of it changed (Node::downstreamChanged: a holding source re-sends its frame). Off the edit:
   *  the edit only notes the node; the edit-requests thread walks upstream of every node noted,
   *  at once and at most every kRerunGap (so an edit costs O(1), not O(what is upstream)). */
  void changedDownstreamOf(detail::NodeState* node, bool itself = false);
  /** That walk (on the edit-requests thread). */
  void tellSourcesDownstreamChanged();
  struct ChangedAt {
    std::weak_ptr<detail::NodeState> node;
    bool itself;
    std::int64_t tick;  // the edit's start (ticks.hpp): a source that began a frame after it needs no re-send
  };
  mutable std::mutex changed_mutex_;  // after edit_mutex_
  mutable std::condition_variable walked_;  // a walk ended
  std::vector<ChangedAt> changed_;  // changed_mutex_: noted since the last walk
  bool walking_ = false;  // changed_mutex_
  std::chrono::steady_clock::time_point last_walk_;  // changed_mutex_
  /** Until no walk is pending or under way (waitIdle: what an edit asked of sources is asked). */
  bool waitWalked(std::chrono::steady_clock::time_point deadline) const;
  static constexpr std::chrono::milliseconds kRerunGap{20};
  /** The node's interface if `param` had `value` (nullptr: as it is); refused with a message
   *  naming the node when the type's interface function fails or breaks a rule. */
  Result<std::shared_ptr<const Manifest>> interfaceFor(const detail::NodeState& node, const std::string& param,
                                                       const ParamValue* value) const;
  /** Gives the node `next` as one edit (graph_interface.cpp); `also` runs inside it. */
  void applyInterface(detail::NodeState* node, std::shared_ptr<const Manifest> next, const std::function<void()>& also = {});
  void removeEvent(std::shared_ptr<detail::EventEdge> edge);

  NodeRegistry registry_;
  std::shared_ptr<const Host> host_;  // edit_mutex_
  std::atomic<bool> rerun_on_edit_{true};  // Graph::setRerunOnEdit
  mutable std::mutex edit_mutex_;  // serialises edits and reads of the structure
  /** edit_mutex_: when its holder took it (ticks.hpp), so before any part of the edit could reach a
   *  firing. A change noted at the end of an edit would be later than a firing that already saw it,
   *  and that source would re-send a frame that had gone through the change. */
  mutable std::int64_t edit_began_ = 0;
  std::map<std::string, NodePtr> nodes_;
  std::map<std::uint64_t, detail::NodeState*> order_;  // insertion order
  std::uint64_t next_seq_ = 0;
  std::map<std::string, int> name_counters_;  // generated names: gaussian_blur_1, _2, ...
  std::map<std::string, std::shared_ptr<detail::ThreadGroup>> groups_;
  detail::Subgraphs subgraphs_;  // by path, and the ones ungrouped
  std::vector<ConnectionDescription> dormant_;  // connections of placeholder nodes, kept verbatim
  std::size_t links_ = 0;  // data, parameter and event links: made in connectDirect, gone in removeEdge/removeEvent
  bool running_ = false;
  bool ran_ = false;  // started at least once: messages may be in flight
  bool paused_ = false;
  bool tracing_ = false;  // Graph::setTracing: new groups trace too
  std::shared_ptr<detail::Revisions> revisions_ = std::make_shared<detail::Revisions>();
  /** Node::requestEdit's queue; stopped first when the graph goes. */
  std::shared_ptr<detail::EditRequests> edits_;
  /** addNode, its parameters set before its setup() runs (NodeDescription's, in order). */
  Result<std::string> addNodeWith(const std::string& type, const std::string& name, const std::string& thread_group,
                                  const std::vector<std::pair<std::string, std::string>>& params);
  /** Parameters of a node not yet in the graph, in order: an interface follows each that shapes it. */
  Status presetParams(detail::NodeState& node, const std::vector<std::pair<std::string, std::string>>& params);
  /** `text` as a value of the node's parameter `param`; refused naming both. */
  Result<ParamValue> parseParam(const detail::NodeState& node, const std::string& param, const std::string& text) const;
  /** Sets a parameter of `node` as setParameter does (under the edit lock). */
  Status setParameterLocked(detail::NodeState& node, int index, const ParamValue& value);
  /** A node's own request (Node::requestEdit), if it is still in the graph; a refusal is its error. */
  void applyRequested(const std::shared_ptr<detail::NodeState>& node, const std::string& param, const ParamValue& value);
  void bump() { revisions_->edit(); }  // an edit: shown, and what a save keeps
};

}  // namespace apex
