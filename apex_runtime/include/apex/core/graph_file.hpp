// The graph file format (versioned YAML). See docs/graph_format.md.
#pragma once

#include <string>

#include "apex/core/description.hpp"
#include "apex/core/graph.hpp"
#include "apex/core/result.hpp"

namespace apex {

inline constexpr int kGraphFormatVersion = 1;
/** A graph file larger than this is refused before it is read (a real graph is a few hundred KiB). */
inline constexpr long kMaxGraphFileBytes = 16L << 20;

/** @brief Parses graph YAML; errors name the line and what is wrong. */
Result<GraphDescription> parseGraphText(const std::string& yaml_text);
/** @brief The canonical text of a graph: loading it and formatting again gives the same text. */
std::string formatGraphText(const GraphDescription& description);

/** @brief A YAML mapping "{gain: 2, mode: mean}" as (name, value text) pairs; "" is no pairs. */
Result<std::vector<std::pair<std::string, std::string>>> parseParameterMap(const std::string& yaml_text);

/** @brief The text of a graph file: only a regular file of at most kMaxGraphFileBytes
 *  (a FIFO or a device is refused at once, never waited on). */
Result<std::string> readGraphFile(const std::string& path);
/** @brief Reads and loads a graph file into `graph`, all or nothing. */
Result<LoadReport> loadGraphFile(Graph& graph, const std::string& path);
/** @brief Saves the graph atomically: the file is either the old one or the whole new one. */
Status saveGraphFile(const Graph& graph, const std::string& path);
/** @brief Writes a temporary file beside `path`, flushes it to disk, renames it over `path`.
 *  Refuses to replace what is not a regular file or has no write bit in its mode; removes
 *  temporary files left beside `path` by saves whose process died. */
Status writeFileAtomically(const std::string& path, const std::string& content);

}  // namespace apex
