// Plain data describing a graph: what the file format reads and writes and what
// a front end shows. No behaviour, no YAML.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace apex {

struct Manifest;
struct GraphDescription;

/** @brief The thread group every graph has, where a node goes unless told otherwise. */
inline constexpr const char* kDefaultGroup = "default";

/** @brief One node as saved: parameter values are YAML text. */
struct NodeDescription {
  std::string name, type;
  std::vector<std::pair<std::string, std::string>> parameters;  ///< name → YAML text, declaration order
  std::vector<std::string> interactive;  ///< parameters with ports: the exact set
  bool enabled = true;
  std::string thread_group = kDefaultGroup;
  std::string ui;  ///< free-form front-end metadata, YAML flow text ("" if none)
  bool placeholder = false;  ///< type unknown here: kept and written back unchanged
  std::string error;  ///< current error (state, not saved)
  /** The instance's ports (state, not saved): its type's manifest, or what the type's
   *  interface function made of it for these parameters; nullptr for placeholders. */
  std::shared_ptr<const Manifest> interface;
  int line = 0;  ///< where it was read from, for messages (0: not from a file)
  /** A subgraph instance (type kSubgraphType): its inner graph, with its exports; `parameters`
   *  and `interactive` then name exported parameters. nullptr for ordinary nodes. */
  std::shared_ptr<const GraphDescription> subgraph;
  /** A file-backed subgraph: the reference as written (`package://apex/graphs/x.yaml`, a path
   *  relative to the file that names it, or absolute); "" for an inline one. */
  std::string source;
};

/** The type a subgraph instance shows (not a registered type id: it cannot clash with one). */
inline constexpr const char* kSubgraphType = "subgraph";

/** @brief What a graph offers when used as a subgraph: one port, parameter or event of the
 *  subgraph node, and the inner ones it stands for ("node/port", relative to the graph). */
struct ExportDescription {
  enum class Kind { Input, Output, Parameter, Slot, Trigger };
  Kind kind = Kind::Input;
  std::string name;
  /** Inputs and slots may stand for several inner ones (they all get what arrives); outputs,
   *  triggers and parameters for exactly one. Each "node/port", node possibly "a/b". */
  std::vector<std::string> inner;
  std::string description;  ///< "" : the inner one's
  int line = 0;
  bool operator==(const ExportDescription& o) const {
    return kind == o.kind && name == o.name && inner == o.inner && description == o.description;
  }
};

/** @brief A connection "from_node/from_port → to_node/to_port": data, parameter or event. */
struct ConnectionDescription {
  std::string from_node, from_port, to_node, to_port;
  int line = 0;
  bool operator==(const ConnectionDescription& o) const {
    return from_node == o.from_node && from_port == o.from_port && to_node == o.to_node && to_port == o.to_port;
  }
};

struct GraphDescription {
  std::vector<std::string> thread_groups;  ///< user groups; "default" always exists
  std::vector<NodeDescription> nodes;
  std::vector<ConnectionDescription> connections;
  std::vector<ExportDescription> exports;  ///< used when the graph is a subgraph; ignored at the top
};

/** @brief One output of a node: what it sent, and the latency of the firings that sent on it. */
struct OutputStats {
  std::string name;
  std::uint64_t sent = 0;  ///< messages sent (not Nothing, not an end of sequence): the rate on its links
  /** As NodeStats' latency, over the firings that sent a message on this output (one that sends
   *  on some frames only has its own figures); -1: none in the window. */
  std::int64_t latency_p50_ns = -1, latency_p95_ns = -1, latency_max_ns = -1;
  std::uint64_t latency_frames = 0;
};

/** @brief Profiling of one node; times in nanoseconds. */
struct NodeStats {
  std::string name;
  std::uint64_t firings = 0;  ///< firings that took or sent a message: frames
  std::uint64_t nothing_firings = 0;  ///< firings that only passed Nothing (not in the rate or times)
  std::uint64_t dropped = 0;  ///< frames a source keeping the newest lost (Node::countDropped)
  /** Its outputs in the node's order: the messages each sent (the rate on its links is their
   *  change over time) and each one's latency. */
  std::vector<OutputStats> outputs;
  /** Firing times: every firing of a node that takes about a microsecond or more; one firing
   *  in 8 of a faster one (a clock read would cost a quarter of its hop), so there max_ns is the
   *  largest sampled time. */
  std::uint64_t last_ns = 0, mean_ns = 0, max_ns = 0;
  /** The firings timed so far and the sum of their times (mean_ns is the one over the other): a
   *  difference of two readings gives the mean over the firings between them. */
  std::uint64_t timed_firings = 0, timed_ns = 0;
  /** The timed firings' median and 95th percentile over the last 5 to 10 seconds (within 1/16). */
  std::uint64_t p50_ns = 0, p95_ns = 0;
  /** Latency over the last 5 to 10 seconds: from the stamp of the frame a firing worked on
   *  (Message::frame) to the end of that firing (when what it sent left), for each firing
   *  whose frame is live (stamped within the last hour: not a bag played at its recorded stamps).
   *  -1: none in the window. Quantiles within 1/16; the mean exact. */
  std::int64_t latency_mean_ns = -1, latency_p50_ns = -1, latency_p95_ns = -1, latency_max_ns = -1;
  std::uint64_t latency_frames = 0;  ///< how many the latency figures are over
  std::string error;
  bool enabled = true;
  /** Set when the node is stalled: it has not fired for a while although data
   *  reached something upstream of it since; says what it waits for, e.g.
   *  "waiting for input 'regions' from 'blobs'". */
  std::string waiting_for;
  double idle_s = 0;  ///< seconds since it last fired (or since it was added)
};

/** @brief One bar of a histogram: durations in [lower_ns, upper_ns), how many. */
struct HistogramBucket {
  double lower_ns = 0, upper_ns = 0;
  std::uint64_t count = 0;
};

/** @brief A node's distributions over the window NodeStats' percentiles are over (the last 5 to
 *  10 s, or since it was added if no status was read yet): its firing times and its latency from
 *  its frames' stamps, the buckets that hold any (log-linear, 8 per power of two). */
struct NodeProfile {
  std::string name;
  double window_s = 0;  ///< how many seconds the counts are over
  std::vector<HistogramBucket> time, latency;
  /** Since the node was added (as NodeStats): its firings, those timed and their summed time. */
  std::uint64_t firings = 0, timed_firings = 0, timed_ns = 0;
};

/** @brief Profiling of one thread group: busy time against wall time since start. */
struct GroupStats {
  std::string name;
  std::uint64_t busy_ns = 0, wall_ns = 0, firings = 0, wakeups = 0;
  double load() const { return wall_ns ? double(busy_ns) / double(wall_ns) : 0.0; }
};

}  // namespace apex
