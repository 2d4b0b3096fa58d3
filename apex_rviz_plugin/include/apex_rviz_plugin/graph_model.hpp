// The panel's model, with no display: the runtime's graph as the latched ~graph
// topic last described it, what may connect to what (for feedback while
// dragging), node positions, and the history of edits as the service calls that
// undo and redo them.
#pragma once

#include <apex/AddNode.h>
#include <apex/Connect.h>
#include <apex/GraphState.h>
#include <apex/Group.h>
#include <apex/NodeTypeInfo.h>
#include <apex/RemoveNode.h>
#include <apex/RenameNode.h>
#include <apex/SetEnabled.h>
#include <apex/SetInteractive.h>
#include <apex/SetParameter.h>
#include <apex/SetThreadGroup.h>
#include <apex/SetUi.h>
#include <apex/Ungroup.h>

#include <map>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

namespace YAML {
class Node;
}

namespace apex_rviz_plugin {

/** @brief How an Optimizer tunes `p`: the words of its dimension after the name ("" a double,
 *  " int", " interval" both ends, " choice" its options, " bool"); nothing for what it cannot
 *  tune (text, paths, colours, lists) or a parameter that shapes its node's ports. */
std::optional<std::string> tunedAs(const apex::ParamInfo& p);

/** @brief The node type that tunes parameters (apex_nodes/generic/optimizer.cpp). */
inline constexpr const char* kOptimizerType = "apex_nodes/Optimizer";

/** @brief The single-object tracker (apex_nodes/opencv/tracking.cpp): its menu can start it on a
 *  box drawn on its frame (tracker_start.hpp). */
inline constexpr const char* kTrackerType = "apex_nodes/Tracker";

/** @brief A point of a two-objective Optimizer's Pareto front (its `front` parameter). */
struct FrontPoint {
  int evaluation = 0;  ///< which evaluation of the run it is (1, 2, ...)
  double fitness = 0;
  double ms_per_frame = 0;  ///< the cost: the tuned nodes' firing time per frame
  std::string values;  ///< {dimension: value} as YAML flow text
};

/** @brief The points of an Optimizer's `front` parameter (YAML text), cheapest first; none if it
 *  holds none, or is not such a list. */
std::vector<FrontPoint> frontIn(const apex::ParamInfo* front);

/** @brief One service call of the runtime's API, with the service's name. */
struct Call {
  std::string service;  ///< e.g. "add_node", "connect", "disconnect"
  std::variant<apex::AddNode::Request, apex::RemoveNode::Request, apex::Connect::Request, apex::SetParameter::Request,
               apex::SetEnabled::Request, apex::SetInteractive::Request, apex::SetThreadGroup::Request, apex::SetUi::Request,
               apex::Group::Request, apex::Ungroup::Request, apex::RenameNode::Request>
      request;
  /** connect only: restoring a connection that may still be there (undo of an edit that may
   *  have dropped it); "already connected" is then success. */
  bool if_missing = false;
};

/** @brief An edit as done, and the calls that undo it. */
struct Edit {
  Edit() = default;
  Edit(std::string label, std::vector<Call> apply, std::vector<Call> revert)
      : label(std::move(label)), apply(std::move(apply)), revert(std::move(revert)) {}
  std::string label;  ///< for a menu: "Add gaussian_blur_1"
  std::vector<Call> apply;  ///< redo: the calls in order
  std::vector<Call> revert;  ///< undo: the calls in order
  /** Edits of one gesture share a key ("node/param" for a slider): an open edit (a drag going
   *  on) takes the next one of its key into the same undo step. */
  std::string merge_key;
  bool open = false;
};

/** @brief A parameter whose value differs from a preset's. */
struct PresetChange {
  std::string node, param;
  std::string now;  ///< "" if the node or parameter is no longer there
  std::string then;  ///< as the preset has it
};

/** @brief What a paste adds: the edit, or why there is none; and the new nodes' names. */
struct Pasted {
  std::optional<Edit> edit;
  std::vector<std::string> names;
  std::string error;
};

/** @brief Whether `port` is one of the events every node has: the slots enable and disable, the
 *  trigger processed. */
bool isBuiltinEvent(const std::string& port);

/** @brief A node type a dragged link may join as a new node, and the port of it the link takes. */
struct NewLink {
  std::string type;  ///< the type's id
  std::string port;  ///< its input, slot or parameter (a link from an output), or its output, trigger or parameter
};

/** @brief A node type a link may take in its place as a new node, and the ports of it the link's
 *  two halves join. */
struct NewInsert {
  std::string type;  ///< the type's id
  std::string in;  ///< its port the link's source feeds
  std::string out;  ///< its port that feeds the link's target
};

class GraphModel {
 public:
  /** @brief Takes a ~graph message; false (and no change) if its revision is not newer. */
  bool update(const apex::GraphState& graph);
  /** @brief Forgets the graph: the next update is taken whatever its revision (a restarted runtime). */
  void reset() {
    has_graph_ = false;
    graph_ = apex::GraphState();
    taken_ui_.clear();
  }
  bool hasGraph() const { return has_graph_; }
  const apex::GraphState& graph() const { return graph_; }
  /** @brief The runtime took `calls` (an edit it answered with success): the next edit of a
   *  node's ui (a collapse right after a pin) builds on the ui they set, until a newer ~graph
   *  comes, rather than on what the ~graph last said. What is shown does not change. */
  void took(const std::vector<Call>& calls);

  const apex::NodeInfo* node(const std::string& name) const;
  /** @brief The nodes `calls` give another path, as (from, to), read before they are sent: a
   *  rename's node, a group's members, an ungrouped subgraph's nodes (the nodes inside a moved
   *  subgraph move with it and are not listed). */
  std::vector<std::pair<std::string, std::string>> moves(const std::vector<Call>& calls) const;
  /** @brief Whether `calls` group or ungroup nodes: the runtime then ends every inspection. */
  static bool regroups(const std::vector<Call>& calls);
  const apex::ParamInfo* parameter(const std::string& node, const std::string& name) const;
  const apex::PortInfo* port(const std::string& node, const std::string& port, const std::string& kind) const;
  /** @brief Whether an output (or trigger, or parameter output) may feed an input (or slot,
   *  or parameter input), with the runtime's rules; if not, why. Empty when it may. */
  std::string whyNot(const std::string& from_node, const std::string& from_port, const std::string& to_node,
                     const std::string& to_port) const;
  /** @brief As whyNot, for a new link that replaces the one feeding the input (as connect() does). */
  std::string whyNotReplacing(const std::string& from_node, const std::string& from_port, const std::string& to_node,
                              const std::string& to_port) const;
  /** @brief The connection feeding an input or parameter input, if any (slots take many). */
  std::optional<apex::Connection> feeding(const std::string& node, const std::string& port) const;
  /** @brief The node's position from its UI metadata ({x: .., y: ..}); (0, 0) if none. */
  std::pair<double, double> position(const std::string& node) const;
  /** @brief The position in UI metadata text ({x: .., y: ..}); (0, 0) if none. */
  static std::pair<double, double> positionIn(const std::string& ui_text);
  /** @brief Whether the node's UI metadata holds a position (a graph written without a panel has none). */
  bool hasPosition(const std::string& node) const;
  /** @brief A name for a new node of `type` inside `parent` ("" for the top level) that no node
   *  there has, nor any path in `reserved` (names sent a moment ago, not shown yet):
   *  GaussianBlur -> gaussian_blur_1. */
  std::string freshName(const std::string& type, const std::string& parent = "",
                        const std::set<std::string>& reserved = {}) const;

  /** @brief A node of `type` named `name` as add_node makes it (and ~graph then shows it): the
   *  type's ports, both ports of each parameter that has ports by default, the parameters at
   *  their defaults. */
  static apex::NodeInfo newNode(const apex::NodeTypeInfo& type, const std::string& name = "");
  /** @brief The types a link dragged from `node`/`port` and let go on empty canvas may join as a
   *  new node (graph_model_new_node.cpp): from an output, trigger or parameter output (`source`),
   *  the types with an input, slot or parameter input that takes it; from an input, slot or
   *  parameter input, those with a port that feeds it (replacing its link, as connect() does).
   *  The runtime's rules decide (whyNot over the graph with the new node in it). Each type with
   *  its first such port, its own ports before the events every node has (enable, disable,
   *  processed); types that only have those come last. Otherwise in the order given. */
  std::vector<NewLink> linkable(const std::vector<apex::NodeTypeInfo>& types, const std::string& node, const std::string& port,
                                bool source) const;
  /** @brief The types a new node put into `link` may be of ("Insert node..." on a link): those with
   *  a port the link's source feeds and one that feeds the link's target in its place, by the
   *  runtime's rules and linkable's choice of ports. Types with fewer of those ports among the
   *  events every node has come first; otherwise in the order given. */
  std::vector<NewInsert> insertable(const std::vector<apex::NodeTypeInfo>& types, const apex::Connection& link) const;

  // --- edits: each returns the calls to make; the model changes when ~graph says so ---
  Edit addNode(const std::string& type, const std::string& name, double x, double y) const;
  /** @brief A new node `name` of `type` at (x, y) and link `c`, one of whose ends is the new node,
   *  as one edit: undone by dropping the link (giving back the one it replaced) and removing the node. */
  Edit addLinked(const std::string& type, const std::string& name, double x, double y, const apex::Connection& c) const;
  /** @brief A new node `name` of `type` at (x, y) put into `link`: the link's source into its port
   *  `in`, its port `out` into the link's target, `link` gone; one edit, undone by giving `link`
   *  back and removing the node. */
  Edit addInserted(const std::string& type, const std::string& name, double x, double y, const apex::Connection& link,
                   const std::string& in, const std::string& out) const;
  /** @brief Removing a node, undone by adding it back with its parameters, group, UI and connections. */
  std::optional<Edit> removeNode(const std::string& name) const;
  /** @brief A new connection; one into an input fed already replaces that link (one edit). */
  Edit connect(const apex::Connection& c) const;
  /** @brief A node with no connections put into `c` (from its first input that takes c's sender
   *  to its first output c's receiver takes) and moved to (x, y); one edit. Nothing if it has
   *  connections or no such ports. */
  std::optional<Edit> insert(const std::string& node, const apex::Connection& c, double x, double y) const;
  Edit disconnect(const apex::Connection& c) const;
  /** @brief `dragging`: one value of a drag going on; the drag's edits are one undo step, closed
   *  by its last value (dragging false). */
  std::optional<Edit> setParameter(const std::string& node, const std::string& param, const std::string& value,
                                   bool dragging = false) const;
  /** @brief Several parameters of one node set as one edit named `label` (e.g. a box's x, y, width
   *  and height), each as setParameter sets it, in the order given; undone in the reverse order.
   *  Nothing if the node or one of the parameters is not there, or `values` is empty. */
  std::optional<Edit> setParameters(const std::string& node, const std::vector<std::pair<std::string, std::string>>& values,
                                    const std::string& label) const;
  /** @brief Parameters back to their defaults: `param`, or every parameter of the node if empty;
   *  one edit. Nothing if the node or parameter is not there, or all are at their defaults. */
  std::optional<Edit> resetToDefault(const std::string& node, const std::string& param = "") const;
  /** @brief A new name for a node in its place (a name, not a path), one edit. */
  std::optional<Edit> rename(const std::string& node, const std::string& new_name) const;
  /** @brief The node's box moved; its other ui metadata (compact or expanded, pins) kept. */
  std::optional<Edit> move(const std::string& node, double x, double y) const;
  /** @brief The node's box expanded (every parameter) or compact (BoxView), one edit. */
  std::optional<Edit> setExpanded(const std::string& node, bool expanded) const;
  /** @brief A parameter pinned to (or unpinned from) the node's compact box, one edit. */
  std::optional<Edit> setPinned(const std::string& node, const std::string& param, bool pinned) const;
  /** @brief Nodes moved to new positions (name -> x, y) as one edit, e.g. "Tidy". Its undo puts
   *  each back where `shown` has it (where the panel shows the box: a drag the runtime's graph does
   *  not show yet), else where the graph has it. */
  std::optional<Edit> arrange(const std::map<std::string, std::pair<double, double>>& positions, const std::string& label,
                              const std::map<std::string, std::pair<double, double>>& shown = {}) const;
  /** @brief `nodes` (of one level) as graph file text, for the clipboard: types, parameters,
   *  ports shown, enabled, groups, positions (from `shown_at` where it has them: where the panel
   *  shows the boxes) and the connections among them. An inline
   *  subgraph is left out (add_node makes subgraphs from files): `left_out` names it. */
  std::string copy(const std::vector<std::string>& nodes, std::string* left_out = nullptr,
                   const std::map<std::string, std::pair<double, double>>& shown_at = {}) const;
  /** @brief Copied nodes (graph file text) added at `level` under names free there (their own if
   *  it is), placed as they were among themselves with their top-left corner at (x, y), connected
   *  among themselves as they were; one edit, undone by removing them. */
  Pasted paste(const std::string& text, const std::string& level, double x, double y) const;
  /** @brief The parameter values of `nodes` (every node if empty) as preset text (YAML). */
  std::string preset(const std::vector<std::string>& nodes) const;
  /** @brief The parameters whose values differ from the preset's; `error` if it is not one. */
  std::vector<PresetChange> compare(const std::string& preset_text, std::string* error = nullptr) const;
  /** @brief The preset's values set where they differ, as one edit named after it; nothing if
   *  none differs or the text is not a preset (`error` says which). */
  std::optional<Edit> restore(const std::string& preset_text, const std::string& name, std::string* error = nullptr) const;
  /** @brief A copy and a paste moved by (dx, dy) from the originals, as one edit. */
  Pasted duplicate(const std::vector<std::string>& nodes, double dx, double dy,
                   const std::map<std::string, std::pair<double, double>>& shown_at = {}) const;
  /** @brief Nodes beside each other into a new subgraph (named subgraph_1, _2, ... at their
   *  level), one edit: undone by ungrouping it. */
  std::optional<Edit> group(const std::vector<std::string>& nodes) const;
  /** @brief A subgraph's nodes up one level, one edit: undone by grouping them again. */
  std::optional<Edit> ungroup(const std::string& subgraph) const;
  std::optional<Edit> setEnabled(const std::string& node, bool enabled) const;
  std::optional<Edit> setThreadGroup(const std::string& node, const std::string& group) const;
  /** @brief Nodes moved to thread groups (node -> group, in order) as one edit named `label`, e.g.
   *  what Balance proposes; undone to the groups they are in now. Nodes not in the graph, or in
   *  that group already, are left out; nothing if none is left. */
  std::optional<Edit> setThreadGroups(const std::vector<std::pair<std::string, std::string>>& moves,
                                      const std::string& label) const;
  std::optional<Edit> setInteractive(const std::string& node, const std::string& param, bool interactive) const;
  /** @brief Tunes a parameter with an Optimizer (`optimizer`, or a new one at (x, y) if
   *  empty): the parameter gets ports, the Optimizer a dimension named after it (its range and
   *  step from the parameter) and the two are connected; one edit. A dimension is an output of
   *  the Optimizer, so never named after one of its own ports, events or parameters: those of
   *  `optimizer_type` (the Optimizer node type as the runtime lists it; nullptr if not known),
   *  and those the Optimizer node in the graph has. Nothing for a parameter it cannot tune
   *  (tunedAs), one that is linked already, an Optimizer that is not there,
   *  or a new Optimizer while its type is not known (its names are not guessed). */
  std::optional<Edit> optimise(const std::string& node, const std::string& param, const std::string& optimizer, double x,
                               double y, const apex::NodeTypeInfo* optimizer_type) const;
  /** @brief The Optimizer's best values (its `best_values`) set on the parameters it tunes, as
   *  one edit; undone to the values they hold now. Nothing before it has best values, or while it runs. */
  std::optional<Edit> applyBest(const std::string& optimizer) const;
  /** @brief A two-objective Optimizer's Pareto front (its `front`), cheapest first; empty if none. */
  std::vector<FrontPoint> front(const std::string& optimizer) const;
  /** @brief The values of the front's point from evaluation `evaluation`, set as applyBest sets
   *  the best: one edit, undone to the values before. Nothing if the front has no such point. */
  std::optional<Edit> applyFrontPoint(const std::string& optimizer, int evaluation) const;
  /** @brief The graph's Optimizer nodes. */
  std::vector<std::string> optimizers() const;

 private:
  /** `values` ({dimension: value}) set on the parameters the Optimizer's dimensions feed. */
  std::optional<Edit> applyValues(const std::string& optimizer, const YAML::Node& values, const std::string& label) const;
  /** This graph without `gone` (if any) and with a node of no type named "new node" at `level`
   *  (last of its nodes), for linkable and insertable to try the types in. */
  GraphModel probe(const std::string& level, const std::optional<apex::Connection>& gone) const;

  /** A node's ui metadata as the edits build on it: the runtime's last taken, else the graph's. */
  const std::string& uiOf(const apex::NodeInfo& n) const;

  apex::GraphState graph_;
  bool has_graph_ = false;
  std::map<std::string, std::string> taken_ui_;  // node -> the ui an answered edit set, until a newer ~graph
};

/** @brief Undo and redo of done edits. A new edit clears what could be redone. */
class EditHistory {
 public:
  /** @brief Adds an edit, or folds it into the open edit of its gesture (same merge key). */
  void done(Edit edit);
  /** @brief Forgets everything (a graph loaded, another runtime). */
  void clear() { undo_.clear(), redo_.clear(); }
  bool canUndo() const { return !undo_.empty(); }
  bool canRedo() const { return !redo_.empty(); }
  /** @brief The calls that undo the last edit (and moves it to the redo list). */
  std::vector<Call> undo();
  std::vector<Call> redo();
  std::string undoLabel() const { return undo_.empty() ? "" : undo_.back().label; }
  std::string redoLabel() const { return redo_.empty() ? "" : redo_.back().label; }
  /** @brief Forgets what could be redone (the graph was edited elsewhere: it no longer applies). */
  void dropRedo() { redo_.clear(); }

 private:
  std::vector<Edit> undo_, redo_;
};

}  // namespace apex_rviz_plugin
