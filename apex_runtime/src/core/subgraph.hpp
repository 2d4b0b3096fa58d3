// A subgraph instance as the graph keeps it. Subgraphs are flattened: their inner
// nodes are ordinary nodes of the one graph, named "<path>/<node>", under the
// same firing rule and invariants; this record is only the façade: the exports
// (what the subgraph's own ports stand for), settings of its own, and what is
// needed to save it back as it was written (inline, or a reference to a file).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "apex/core/description.hpp"

namespace apex {
namespace detail {

struct Subgraph {
  std::string path;    // "detector", "detector/stage"
  std::string source;  // the file reference as written; "" inline
  std::uint64_t seq = 0;  // its place among the nodes (insertion order)
  std::vector<std::string> thread_groups;
  std::vector<ExportDescription> exports;  // inner endpoints relative to `path`
  bool enabled = true;
  std::string ui;
  /** File-backed: its inner graph as the file made it (canonical text, exported parameters
   *  masked). Saved as a reference while the inner graph still reads so; else inline. */
  std::string baseline;
  std::map<std::string, std::string> defaults;  // exported parameter → value the file gave it
};

/** "a/b/c" → "a/b"; "a" → "" */
inline std::string parentOf(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash);
}

/** join("a", "b") → "a/b"; join("", "b") → "b" */
inline std::string join(const std::string& prefix, const std::string& name) {
  return prefix.empty() ? name : prefix + "/" + name;
}

/** "node/port" at its last '/'. */
inline std::pair<std::string, std::string> splitEnd(const std::string& text) {
  const auto slash = text.rfind('/');
  if (slash == std::string::npos) return {text, ""};
  return {text.substr(0, slash), text.substr(slash + 1)};
}

inline bool sendingExport(ExportDescription::Kind k) {
  return k == ExportDescription::Kind::Output || k == ExportDescription::Kind::Trigger ||
         k == ExportDescription::Kind::Parameter;
}
inline bool receivingExport(ExportDescription::Kind k) {
  return k == ExportDescription::Kind::Input || k == ExportDescription::Kind::Slot ||
         k == ExportDescription::Kind::Parameter;
}

}  // namespace detail
}  // namespace apex
