// A frame trace: the last firings of every thread group (Graph::setTracing, Graph::trace), and
// their export in Chrome's trace event format, which Perfetto and chrome://tracing open.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace apex {

/** @brief One firing: which node, when, and the frame it worked on. */
struct TraceFiring {
  std::string node;  ///< its path when the trace was read; "(removed)" if it has gone since
  std::string type;  ///< its type's id
  std::int64_t start_ns = 0, end_ns = 0;  ///< since the trace's time 0 (Trace::start_wall_ns)
  std::int64_t frame = 0;  ///< the stamp (ns) of the frame it took in or sent (Message::frame); 0: unknown
  bool starts_frame = false;  ///< it began the frame: took none in, sent a stamped message (a source)
};

/** @brief One thread group's firings, oldest first. */
struct TraceGroup {
  std::string name;
  std::vector<TraceFiring> firings;
};

/** @brief The last firings of every thread group. */
struct Trace {
  std::int64_t start_wall_ns = 0;  ///< the wall-clock time of time 0, ns since the epoch
  std::vector<TraceGroup> groups;
  std::size_t size() const;
};

/** @brief The trace as Chrome trace event JSON: a track per thread group named after it, a complete
 *  event ("X") per firing named after its node (its type as the category, its frame's stamp in
 *  its args), and a flow ("s", "t", "f") through the firings of each frame, in the order they
 *  started. A firing that begins the frame again (a bag played in a loop replays its stamps), or
 *  a node already in the flow, starts a new flow. `process` names the one process track. */
std::string chromeTraceJson(const Trace& trace, const std::string& process);

}  // namespace apex
