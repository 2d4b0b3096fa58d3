// The recovery copy of a runtime's graph (issue #35): unsaved edits live only in the runtime, so
// after each burst of edits it writes the graph whole to $ROS_HOME/apex/recovery/<node>.yaml. A
// save, a graph as it was loaded, or a clean stop leaves no copy: only a crash or a kill does. A
// copy a previous run left is set aside at start (<node>.previous.yaml) and offered through
// ~recovery until a client restores or discards it; the runtime never loads it by itself.
// Owner: RuntimeHost's Impl. tick() runs on its change timer, the rest in service callbacks:
// every member is guarded by one mutex.
#pragma once

#include <ros/node_handle.h>
#include <ros/service_server.h>

#include <apex/LoadGraph.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>

#include "apex/core/result.hpp"

namespace apex {
namespace ros_host {

/** After the last edit, how long the edit revision stays put before the copy is written, and how
 *  long edits that go on wait at most: a copy within a second of any edit (on a 100 ms tick). */
struct RecoveryTiming {
  std::chrono::milliseconds quiet{300}, at_most{800};
};

class Recovery {
 public:
  using Clock = std::chrono::steady_clock;
  /** The graph as a graph file's text, its number of nodes, and its edit revision
   *  (Graph::editRevision) read before the text. */
  struct Snapshot {
    std::string text;
    std::size_t nodes = 0;
    std::uint64_t revision = 0;
  };
  /** A copy a previous run left. */
  struct Offer {
    std::string path;
    std::int64_t written_ns = 0;  // its modification time, since the epoch
    std::size_t nodes = 0;  // top-level nodes; 0 if it does not parse (a restore says why)
  };
  using Timing = RecoveryTiming;

  /** @brief Copies go in `folder` (made if missing) under fileName(node). A copy found there is set
   *  aside and offered (it replaces an older one still offered: the newer unsaved work wins). */
  Recovery(const std::string& folder, const std::string& node, Timing timing = {});
  /** @brief "/robot1/apex" -> "robot1_apex": a runtime's copy, named after its node. */
  static std::string fileName(const std::string& node);

  /** @brief The graph is as a file has it (the start-up graph, one loaded or just saved): no copy
   *  until the next edit; this run's copy, if any, is removed. */
  void saved(const Snapshot& graph);
  /** @brief On a timer: once the edit revision has stayed the same `quiet` after an edit (or edits
   *  have gone on for `at_most`), writes the graph whole if it differs from the saved one and
   *  from the copy, or removes the copy if it is as saved or empty. What nodes report of
   *  themselves (a player's frame) changes the text, not the revision: no copy without an edit.
   *  A failure to write is logged once (until a write succeeds), naming the file; nothing stops. */
  void tick(std::uint64_t revision, const std::function<Snapshot()>& snapshot, Clock::time_point now = Clock::now());
  /** @brief Clean stop: this run's copy removed, no more written. An offered copy stays offered. */
  void close();

  /** @brief Whether the graph differed from the saved one at the last check (a moment after the
   *  last edit): what a save would keep. */
  bool unsaved() const;
  std::optional<Offer> offer() const;
  /** @brief The offered copy was loaded: it becomes this run's copy (moved to its place), and the
   *  graph counts as unsaved until saved. */
  Status adopt();
  /** @brief Deletes the offered copy. */
  Status discard();

  const std::string& path() const { return path_; }

 private:
  void removeOwn();  // (under mutex_)
  void write(const Snapshot& now);  // (under mutex_)

  const std::string path_, offered_path_;
  const Timing timing_;
  mutable std::mutex mutex_;
  std::optional<Offer> offer_;
  std::optional<std::string> saved_;  // none: in no file of the user's (restored from a copy)
  std::optional<std::string> written_;  // the text of this run's copy; none if there is none
  std::uint64_t seen_revision_ = ~0ull;
  bool pending_ = false, closed_ = false, warned_ = false, unsaved_ = false;
  Clock::time_point first_change_, last_change_;
};

/** @brief Serves ~recovery (Recovery.srv): reports the offered copy; "restore" loads it with
 *  `load` (load_graph's own handler: the same checks and limits), "discard" deletes it. */
ros::ServiceServer serveRecovery(ros::NodeHandle& pnh, Recovery& recovery,
                                 std::function<bool(LoadGraph::Request&, LoadGraph::Response&)> load);

}  // namespace ros_host
}  // namespace apex
