// The limits of a graph, one set for the graph files and for every edit: a graph the runtime
// holds can always be saved and loaded back. Far above real graphs (the demo has 12 nodes);
// beyond one, an edit or a file is refused with a message naming the limit.
#pragma once

#include <cstddef>

namespace apex {

inline constexpr std::size_t kMaxGraphNodes = 20000;  ///< in the whole graph, inside subgraphs too
inline constexpr std::size_t kMaxGraphConnections = 100000;  ///< data, parameter and event links
inline constexpr std::size_t kMaxGraphGroups = 256;  ///< thread groups: each is an OS thread
inline constexpr std::size_t kTraceFirings = 1 << 16;  ///< kept per thread group while tracing (2 MiB)
inline constexpr std::size_t kMaxNameLength = 200;  ///< a node's, a group's, one part of a path
inline constexpr int kMaxSubgraphDepth = 16;  ///< subgraphs within subgraphs, inline or from files
inline constexpr long kMaxGraphFileBytes = 16L << 20;  ///< a graph file, checked before reading
inline constexpr int kMaxYamlDepth = 32;  ///< nesting, e.g. inside a node's `ui`
inline constexpr std::size_t kMaxYamlNodes = 2000000;  ///< values in a file, counted through aliases
inline constexpr std::size_t kMaxYamlString = 1 << 16;  ///< characters in one value: a parameter's, a ui's

}  // namespace apex
