// The graph file format (versioned YAML). See docs/graph_format.md.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "apex/core/description.hpp"
#include "apex/core/graph.hpp"
#include "apex/core/limits.hpp"
#include "apex/core/result.hpp"

namespace apex {

/** 2: subgraphs and exports (docs/graph_format.md); files of format 1 load unchanged. */
inline constexpr int kGraphFormatVersion = 2;
/** @brief Parses graph YAML; errors name the line and what is wrong. */
Result<GraphDescription> parseGraphText(const std::string& yaml_text);
/** @brief The canonical text of a graph: loading it and formatting again gives the same text. */
std::string formatGraphText(const GraphDescription& description);

/** @brief A YAML mapping "{gain: 2, mode: mean}" as (name, value text) pairs; "" is no pairs. */
Result<std::vector<std::pair<std::string, std::string>>> parseParameterMap(const std::string& yaml_text);

/** @brief The text of a graph file: only a regular file of at most kMaxGraphFileBytes
 *  (a FIFO or a device is refused at once, never waited on). */
Result<std::string> readGraphFile(const std::string& path);
/** @brief How a graph file and the subgraph files it names are read. */
struct GraphFileOptions {
  /** Sees each ordinary node's description first, at every level of subgraphs; may refuse it
   *  (the load is then refused, naming the file and line) or rewrite its parameters (e.g.
   *  resolve paths). */
  std::function<Status(NodeDescription&)> check;
  /** The file to open for a subgraph reference, given as joinReference() made it; may refuse
   *  it. Default: the path as it is (package:// is then refused: only a ROS host knows packages). */
  std::function<Result<std::string>(const std::string& path)> open;
};

/** @brief A subgraph reference as a path: a relative one is relative to the folder of the file
 *  `from` that names it; absolute paths, `package://`, `$(find pkg)` and `~` stay as they are. */
std::string joinReference(const std::string& ref, const std::string& from);

/** @brief Reads a graph file and, into each file-backed subgraph node, the file it names
 *  (recursively; a file that includes itself, or nesting deeper than kMaxSubgraphDepth, is
 *  refused). Errors name the file and line, through every level. */
Result<GraphDescription> readGraphDescription(const std::string& path, const GraphFileOptions& options = {});
/** @brief readGraphDescription(), then Graph::load: all or nothing. */
Result<LoadReport> loadGraphFile(Graph& graph, const std::string& path, const GraphFileOptions& options = {});
/** How a write reaches its folder. */
enum class Links {
  Follow,  ///< as the path says, links and all (a path the user gave)
  /** No link on the way: each folder opened without following one. For a path resolved and
   *  checked before (FileRoots), which a link swapped in after the check must not redirect. */
  Refuse,
};
/** @brief Saves the graph atomically: the file is either the old one or the whole new one. Replaces
 *  only a graph file (a YAML mapping with `apex_graph`) or an empty file; anything else (a bag, an
 *  image, notes) is refused, naming the file, and left as it is. */
Status saveGraphFile(const Graph& graph, const std::string& path, Links links = Links::Follow);
/** @brief Writes a temporary file beside `path`, flushes it to disk, renames it over `path`, all
 *  in the one folder opened first: no temporary file is left anywhere, whatever happens to the
 *  path meanwhile. Refuses to replace what is not a regular file (a link too) or has no write bit
 *  in its mode; removes temporary files left beside `path` by saves whose process died. */
Status writeFileAtomically(const std::string& path, const std::string& content, Links links = Links::Follow);

}  // namespace apex
