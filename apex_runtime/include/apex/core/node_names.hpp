// The name a new node of a type gets, one rule for the runtime (add_node without a name) and the
// panel (a node dropped from the palette); and how messages name a node, a subgraph or a port.
#pragma once

#include <cctype>
#include <string>

namespace apex {

/** @brief A type's name in snake_case, without its package: "apex_nodes/GaussianBlur" →
 *  "gaussian_blur", "HSVFilter" → "hsv_filter", "PointCloud2Publisher" → "point_cloud2_publisher".
 *  A new node is this and "_1", "_2", ... */
inline std::string nodeBaseName(const std::string& type) {
  const std::string tail = type.substr(type.find('/') + 1);
  auto upper = [&](std::size_t i) { return i < tail.size() && std::isupper(static_cast<unsigned char>(tail[i])); };
  auto lower = [&](std::size_t i) { return i < tail.size() && std::islower(static_cast<unsigned char>(tail[i])); };
  std::string out;
  for (std::size_t i = 0; i < tail.size(); ++i) {
    // a word starts at a capital after a lower-case letter or digit, or at the last capital of a
    // run followed by a lower-case letter (HSV|Filter)
    if (upper(i) && i > 0 && (!upper(i - 1) || lower(i + 1)) && tail[i - 1] != '_') out += '_';
    out += static_cast<char>(std::tolower(static_cast<unsigned char>(tail[i])));
  }
  return out;
}

/** @brief A node as messages name it: "node 'blur'". */
inline std::string nodeLabel(const std::string& node) { return "node '" + node + "'"; }

/** @brief A node with its type: "node 'blur' (apex_nodes/GaussianBlur)". */
inline std::string nodeLabel(const std::string& node, const std::string& type) { return nodeLabel(node) + " (" + type + ")"; }

/** @brief A subgraph as messages name it: "subgraph 'stage'". */
inline std::string subgraphLabel(const std::string& subgraph) { return "subgraph '" + subgraph + "'"; }

/** @brief A port of a node, `kind` being "input", "parameter", ...: "parameter 'sigma' of node 'blur'". */
inline std::string portLabel(const std::string& kind, const std::string& port, const std::string& node) {
  return kind + " '" + port + "' of " + nodeLabel(node);
}

}  // namespace apex
