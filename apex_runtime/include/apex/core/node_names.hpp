// The name a new node of a type gets, one rule for the runtime (add_node without a name) and the
// panel (a node dropped from the palette).
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

}  // namespace apex
