// Edits a node asks for itself (Node::requestEdit): e.g. a plugin host that learns what its
// plugin offers only once loaded, in setup(), and must change its own parameters then. Node
// code runs on a thread group, where an edit cannot be made (it would wait for that very
// group), so the request waits here and one thread of the graph's applies it as an edit. The same
// thread describes the graph for a node that asks (Node::describeGraph), and tells holding sources
// that something downstream of them changed (Graph::Impl::changedDownstreamOf: off the edit).
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "apex/core/node.hpp"
#include "apex/core/param.hpp"

namespace apex {
namespace detail {

class NodeState;

class EditRequests {
 public:
  /** Makes the edit; the node may be gone from the graph by then (check). */
  using Apply = std::function<void(const std::shared_ptr<NodeState>& node, const std::string& param, const ParamValue& value)>;

  /** The graph as plain data, and a maker of graphs like it (Node::describeGraph). */
  using Describe = std::function<GraphSnapshot()>;

  EditRequests(Apply apply, Describe describe) : apply_(std::move(apply)), describe_(std::move(describe)) {}
  ~EditRequests() { stop(); }
  EditRequests(const EditRequests&) = delete;
  EditRequests& operator=(const EditRequests&) = delete;

  /** Queues a request (replacing one of the same node and parameter not yet applied); its
   *  thread starts at the first. After stop(): dropped. */
  void push(std::weak_ptr<NodeState> node, std::string param, ParamValue value);
  /** Queues a description of the graph for `done` (called on this thread). After stop(): dropped. */
  void describe(std::function<void(GraphSnapshot)> done);
  /** Runs `task` on this thread once `due` has come (after the requests queued before it). One
   *  at a time: while one waits, another is not taken (false), as the one waiting does it all. */
  bool runAt(std::chrono::steady_clock::time_point due, std::function<void()> task);
  /** Applies nothing more: waits for a request being applied, drops the rest. Idempotent. */
  void stop();

 private:
  struct Request {
    std::weak_ptr<NodeState> node;
    std::string param;
    ParamValue value;
    std::function<void(GraphSnapshot)> described;  // a description's, not an edit
  };
  void run();
  /** Runs `fn` unlocked, a failure logged as `what` failed. */
  void unlocked(std::unique_lock<std::mutex>& lock, const char* what, const std::function<void()>& fn);

  Apply apply_;
  Describe describe_;
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<Request> queue_;
  std::function<void()> timed_;  // runAt's task, if one waits
  std::chrono::steady_clock::time_point due_;
  bool stopped_ = false;
  std::thread worker_;
};

}  // namespace detail
}  // namespace apex
