// The categories of node types (a manifest's `category`), in the order the panel's palette and
// docs/nodes.md list them: one list for both (apex_nodes/tools/node_docs.hpp, apex_rviz_plugin's
// palette). Other categories follow alphabetically, then the types without one, under "other".
#pragma once

#include <string>
#include <vector>

namespace apex {

inline const std::vector<std::string>& nodeCategories() {
  static const std::vector<std::string> names{"image filters",
                                              "colour",
                                              "contours and shapes",
                                              "segmentation",
                                              "features",
                                              "motion",
                                              "detection",
                                              "drawing",
                                              "cameras and stereo",
                                              "depth",
                                              "learning",
                                              "evaluation",
                                              "clouds",
                                              "cloud segmentation",
                                              "cloud features",
                                              "cloud registration",
                                              "ROS I/O",
                                              "flow",
                                              "math",
                                              "optimisation"};
  return names;
}

/** The heading of types without a category. */
inline const std::string kOtherCategory = "other";

}  // namespace apex
