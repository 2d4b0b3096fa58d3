// Which rviz display shows a ROS message type (the one table the port menu and the double-click
// use), and which displays the panel made follow which node's port as the graph changes: renamed
// with the node, removed with it or its port, disabled while the node cannot run or its port is
// not inspected. Plain C++: GraphPanel applies the changes to rviz; tests check them without it.
#pragma once

#include <apex/GraphState.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace apex_rviz_plugin {

/** @brief An rviz display class and the name of its topic property ("" for one without: rviz/TF). */
struct RvizDisplay {
  std::string rviz_class;
  std::string topic_property;
};

/** @brief The display that shows `message_type` (e.g. "sensor_msgs/Image": rviz/Image, its
 *  "Image Topic"); none for a type rviz has no display for. */
std::optional<RvizDisplay> rvizDisplayFor(const std::string& message_type);

/** @brief Why a port of `message_type` cannot be shown in rviz, for the menu entry's tooltip;
 *  "" if it can. */
std::string noRvizDisplayReason(const std::string& message_type);

/** @brief What a followed display needs after a graph change. */
struct DisplayChange {
  enum class Kind { kRename, kRemove, kEnable, kDisable };
  Kind kind;
  int id;
  std::string node, port;  ///< what it follows now (kRename: inspect it there for its new topic)
  std::string name;  ///< kRename: the display's new name
};

/** The displays the panel made ("apex: <node>/<port>"), by id; a display made by hand is never
 *  one of them. A display is enabled while its node can run (every input it needs linked) and
 *  its port is inspected under the node's current name. */
class FollowedDisplays {
 public:
  /** @brief "apex: <node>/<port>". */
  static std::string displayName(const std::string& node, const std::string& port);
  /** @brief The port was inspected (its topic known): the id of its display, new on the first
   *  call; the display is enabled again if its node can run. */
  int follow(const std::string& node, const std::string& port);
  /** @brief The id of node/port's display, or -1. */
  int find(const std::string& node, const std::string& port) const;
  /** @brief Whether the display should be enabled now; false for an id not followed. */
  bool enabled(int id) const;
  /** @brief Stops following a display (deleted in rviz). */
  void forget(int id);
  /** @brief A rename sent to the runtime (`to`: the node's new path): when a graph has `to` and
   *  not `from`, the displays of `from` and of the nodes inside it follow `to`, instead of being
   *  removed with `from`. */
  void expectRename(const std::string& from, const std::string& to);
  /** @brief The changes `graph` brings, each reported once: kRename for an expected rename
   *  (then disabled until follow() under the new name), kRemove for a node or port that is gone
   *  (forgotten then), kDisable / kEnable when whether it should be enabled changes. */
  std::vector<DisplayChange> update(const apex::GraphState& graph);

 private:
  struct Followed {
    std::string node, port;
    bool runnable = true;  // every input its node needs is linked
    bool inspected = true;  // its topic is known under the node's current name
  };
  /** The path `node` has after the expected renames that `graph` shows done, or "". */
  std::string renamedPath(const std::string& node, const apex::GraphState& graph) const;

  std::map<int, Followed> followed_;
  std::map<std::string, std::string> renames_;  // from -> to: sent, not yet seen in a graph
  int next_id_ = 0;
};

}  // namespace apex_rviz_plugin
