// Candidates evaluated by other runtimes: an Optimizer's `remote_workers` send candidates to the
// Optimizer of the same name in other runtimes (on this machine or another), which evaluates each
// in a copy of the part its fitness comes from and answers with the score. The Optimizer is
// ROS-free; the transport is the host's (the ROS one, in apex_nodes_ros, serves each Optimizer at
// `~<name>/evaluate`, srv/EvaluateCandidate.srv). Without a transport a run with remote workers is
// refused, and no Optimizer serves.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace apex {
class Node;
}

namespace apex_nodes {
namespace tuning {

/** @brief A candidate's values: per Optimizer output (a dimension), its value as YAML text. */
using CandidateValues = std::vector<std::pair<std::string, std::string>>;

/** @brief What another runtime answered for one candidate. */
struct RemoteOutcome {
  std::string error;  ///< empty if it was evaluated; else why not, naming the runtime
  double fitness = 0;
  double ms_per_frame = 0;  ///< when asked for: the cost, as the Optimizer's second objective
};

/** @brief How candidates travel between runtimes. Its functions may be called from any thread. */
class RemoteWorkers {
 public:
  using Done = std::function<void(RemoteOutcome)>;
  /** Handles one request from another runtime; `reply` is called exactly once, from any thread. */
  using Serve = std::function<void(CandidateValues values, bool with_cost, Done reply)>;
  virtual ~RemoteWorkers() = default;
  /** @brief Sends `values` to the Optimizer `optimizer` of the runtime `runtime` (e.g. "/robot2/apex");
   *  `done` is called once, from another thread, with its answer or an error. */
  virtual void evaluate(const std::string& runtime, const std::string& optimizer, CandidateValues values, bool with_cost,
                        Done done) = 0;
  /** @brief Serves the Optimizer `node` to other runtimes until the handle is dropped (dropping it
   *  waits for calls of `serve` under way); nullptr when its host offers no transport. */
  virtual std::shared_ptr<void> serve(const apex::Node& node, Serve serve) = 0;
};

/** @brief The transport of this process (set by the host's node library when it loads), or nullptr. */
std::shared_ptr<RemoteWorkers> remoteWorkers();
/** @brief Sets (or, with nullptr, clears) the transport; returns the one before. */
std::shared_ptr<RemoteWorkers> setRemoteWorkers(std::shared_ptr<RemoteWorkers> transport);

}  // namespace tuning
}  // namespace apex_nodes
