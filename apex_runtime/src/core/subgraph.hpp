// A subgraph instance as the graph keeps it. Subgraphs are flattened: their inner
// nodes are ordinary nodes of the one graph, named "<path>/<node>", under the
// same firing rule and invariants; this record is only the façade: the exports
// (what the subgraph's own ports stand for), settings of its own, and what is
// needed to save it back as it was written (inline, or a reference to a file).
// detail::Subgraphs keeps a graph's records and the rules about them (subgraphs.cpp).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "apex/core/description.hpp"
#include "apex/core/result.hpp"

namespace apex {
namespace detail {

struct Subgraph {
  std::string path;  // "detector", "detector/stage"
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

/** Every subgraph of one graph, by path, and the ones ungrouped last: the rules that need
 *  only these records (what a path may name, what a subgraph's ports stand for, how records
 *  follow a rename, nesting a flat description) in one place. The nodes are the graph's: what
 *  needs them (checking exports, a façade, grouping) is in graph_subgraph.cpp. Used under
 *  the graph's edit mutex. */
class Subgraphs {
 public:
  using Records = std::map<std::string, std::shared_ptr<Subgraph>>;

  /** The subgraph at `path`, or nullptr. */
  std::shared_ptr<Subgraph> find(const std::string& path) const;
  const Records& all() const { return records_; }
  /** The paths of the subgraphs directly in `path`. */
  std::vector<std::string> inside(const std::string& path) const;
  /** "" if `path` may name a new node or subgraph: free (`node_there`: a node has it), each
   *  part a name, its parent a subgraph. */
  std::string checkNewPath(const std::string& path, bool node_there) const;
  /** False if a subgraph around `path` is disabled: everything inside it is. */
  bool enabledAround(const std::string& path) const;

  /** What "node/port" stands for as a sender (outputs, parameter outputs, triggers) or as
   *  receivers (inputs, parameter inputs, slots): itself, or the inner ones a subgraph exports. */
  Result<std::pair<std::string, std::string>> sender(const std::string& node, const std::string& port) const;
  Result<std::vector<std::pair<std::string, std::string>>> receivers(const std::string& node, const std::string& port) const;
  /** An exported parameter's inner node and parameter (through nested subgraphs). */
  Result<std::pair<std::string, std::string>> exportedParam(const std::string& node, const std::string& param) const;

  /** Keeps `sg` at its path, in place of one there. */
  void put(std::shared_ptr<Subgraph> sg);
  /** Forgets the subgraph `path` and every one inside it. */
  void erase(const std::string& path);
  /** Forgets every subgraph, and what was ungrouped. */
  void clear();
  /** Renames the subgraphs at or in `from` (a node's or a subgraph's path) to `to`, and the
   *  exports naming anything that moved. */
  void move(const std::string& from, const std::string& to);
  /** Exports stop standing for `node` (a node or subgraph that goes); exports left standing
   *  for nothing go. */
  void dropExportsOf(const std::string& node);
  /** Takes the subgraph `path` out (ungroup; it exists): its parent's exports that stood for
   *  its exports stand for what those stood for. */
  void dissolve(const std::string& path);
  /** Keeps `sg`, just ungrouped, with its nodes' names after it: what group(restore) brings back. */
  void recordUngrouped(std::shared_ptr<Subgraph> sg, std::set<std::string> members);
  /** The subgraph `path` as ungrouped, if `members` are the nodes it had (taken out of the record). */
  std::shared_ptr<Subgraph> takeUngrouped(const std::string& path, const std::vector<std::string>& members);

  /** The flat description (every node by its path) nested into subgraphs. */
  GraphDescription nest(const GraphDescription& flat) const;

 private:
  Records records_;  // by path
  /** Subgraphs ungrouped, by path, with their nodes' names after it. */
  std::map<std::string, std::pair<std::shared_ptr<Subgraph>, std::set<std::string>>> ungrouped_;
};

/** The inner graph's canonical text with its exported parameters left out: what a
 *  file-backed subgraph is compared by (Subgraph::baseline). */
std::string maskedText(const GraphDescription& inner, const std::vector<ExportDescription>& exports);

/** "input", "output", ... */
const char* kindName(ExportDescription::Kind kind);

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

/** `path` once `from` is called `to`: "from/x" → "to/x"; other paths stay. */
inline std::string movedPath(const std::string& path, const std::string& from, const std::string& to) {
  if (path == from) return to;
  return path.compare(0, from.size() + 1, from + "/") == 0 ? to + path.substr(from.size()) : path;
}

inline bool sendingExport(ExportDescription::Kind k) {
  return k == ExportDescription::Kind::Output || k == ExportDescription::Kind::Trigger || k == ExportDescription::Kind::Parameter;
}
inline bool receivingExport(ExportDescription::Kind k) {
  return k == ExportDescription::Kind::Input || k == ExportDescription::Kind::Slot || k == ExportDescription::Kind::Parameter;
}

}  // namespace detail
}  // namespace apex
