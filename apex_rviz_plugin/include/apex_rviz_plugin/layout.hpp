// Where node boxes go: a layered left-to-right layout of a graph (graphviz's dot
// does it), and a free place for a box among others. Scene units; no display.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace apex_rviz_plugin {

struct Box {
  double x = 0, y = 0, width = 0, height = 0;  ///< top-left corner and size
  bool overlaps(const Box& o, double gap = 0) const {
    return x < o.x + o.width + gap && o.x < x + width + gap && y < o.y + o.height + gap && o.y < y + height + gap;
  }
};

/** @brief Top-left corners for boxes of these sizes (name -> box; x and y are ignored), in
 *  layers from sources on the left to sinks on the right along `edges` (from, to), at least
 *  `gap` apart, the first corner at (0, 0). Cycles are fine. */
std::map<std::string, std::pair<double, double>> layeredLayout(const std::map<std::string, Box>& boxes,
                                                               const std::vector<std::pair<std::string, std::string>>& edges,
                                                               double gap = 40);

/** @brief The place nearest to `wanted` (down first, then right) where it overlaps none of
 *  `taken`, kept `gap` apart. */
Box freePlace(Box wanted, const std::vector<Box>& taken, double gap = 20);

/** @brief Boxes that lie on others moved down, top to bottom, each just below what it lay on
 *  (e.g. after boxes grew); x kept. The new corners of the boxes that moved. */
std::map<std::string, std::pair<double, double>> pushDown(const std::map<std::string, Box>& boxes, double gap = 20);

}  // namespace apex_rviz_plugin
