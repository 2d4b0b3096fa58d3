// What a node's box shows: compact by default (its name, its ports, a few parameters),
// expanded on demand, as in CS::APEX and Groot2. The choice lives in the node's ui
// metadata beside its position (`expanded`, `pinned`), so it is saved with the graph
// and every panel on the runtime shows the same box. No display here: the rule alone.
#pragma once

#include <apex/NodeInfo.h>

#include <optional>
#include <string>
#include <vector>

namespace apex_rviz_plugin {

struct BoxView {
  /** A box with at most this many parameters shows them all: a toggle would cost a row itself. */
  static constexpr std::size_t kFewParams = 3;

  std::optional<bool> expanded;  ///< absent: compact if the node has more than kFewParams parameters
  std::vector<std::string> pinned;  ///< shown in the compact box too
  /** Set by the box, not the metadata: shown compact as if pinned (a player's frame slider), and
   *  left out compact because the box shows them another way (a player's transport bar). */
  std::vector<std::string> always, elsewhere;

  /** @brief From ui metadata text, e.g. "{x: 10, y: 20, expanded: true, pinned: [block_size]}". */
  static BoxView of(const std::string& ui_text);

  /** @brief Whether the box shows every parameter (a legacy one at its default aside). */
  bool isExpanded(const apex::NodeInfo& node) const;
  /** @brief The parameters the box shows, in the type's order: expanded, all of them; compact,
   *  those pinned (or `always`), its files and folders (paths: a node needs them), those set
   *  away from their defaults and those with ports, but
   *  not those shown `elsewhere`. Never a legacy
   *  parameter at its default (ParamInfo::legacy): new boxes do not show what old files need. */
  std::vector<std::string> shown(const apex::NodeInfo& node) const;
  /** @brief How many parameters the compact box leaves out (the toggle says so). */
  std::size_t hidden(const apex::NodeInfo& node) const;
  bool isPinned(const std::string& param) const;
  /** @brief More than kFewParams parameters to list: a compact box can leave some out. */
  static bool collapsible(const apex::NodeInfo& node);
};

/** @brief A number as a box shows it: six significant digits, but a large one (a stamp, 1.7e9 s)
 *  whole with up to three decimals, never in exponent form where it fits in 15 digits. */
std::string scalarText(double v);
/** @brief A box's second line: the node's type, and its thread group when it is not the default
 *  one ("[default]" on every box read as "defaults"). */
std::string kindLine(const std::string& type, const std::string& thread_group);
/** @brief Where a player is: "frame F / N · T s" (F as its `frame` parameter counts, from 0; N
 *  frames, when known), "ended · ..." on the last frame of a pass that does not loop (held there),
 *  "held · ..." when paused. */
std::string playerPlace(long frame, long last, bool last_known, double time_s, bool playing, bool loops);

/** @brief The ui metadata with one key set to a YAML value, every other key kept (the position,
 *  another front end's keys); metadata that is not a map is replaced by a map. */
std::string withUiKey(const std::string& ui_text, const std::string& key, const std::string& yaml_value);
/** @brief The ui metadata placed at (x, y), its other keys kept. */
std::string withPosition(const std::string& ui_text, double x, double y);

}  // namespace apex_rviz_plugin
