// The serving side of an Optimizer's remote workers (remote_workers.hpp): candidates other runtimes
// send are evaluated in copies of the part this Optimizer's fitness comes from (evaluation_copies.hpp),
// as many at once as it has workers, the rest waiting in order. The copies are made when a request
// comes and kept while the part stays as it was, so each candidate sees the graph as it is now.
// Every function runs on the Optimizer's thread group, except that the copies call `later` from theirs.
#pragma once

#include <algorithm>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apex/core/node.hpp"
#include "apex_nodes/remote_workers.hpp"
#include "evaluation_copies.hpp"

namespace apex_nodes {
namespace tuning {

class CandidateServer {
 public:
  /** What the server needs of its Optimizer. */
  struct Hooks {
    std::function<void(std::function<void(const apex::GraphSnapshot&)>)> describe;  // Node::describeGraph
    std::function<void(std::function<void()>)> later;  // Node::runLater, from any thread, dropped once it is gone
    std::function<void(const std::string&)> said;  // what it did, for the Optimizer's state
  };
  explicit CandidateServer(Hooks hooks) : hooks_(std::move(hooks)) {}
  ~CandidateServer() { close("the optimizer '" + optimizer_ + "' was removed"); }

  /** A request to the Optimizer named `optimizer`: evaluated with `workers` copies at most;
   *  `reply` gets its score or an error. */
  void ask(const std::string& optimizer, CandidateValues values, bool with_cost, RemoteWorkers::Done reply, int workers);
  /** Every request waiting or under way answered with `why`, and the copies dropped. */
  void close(const std::string& why);
  /** Candidates evaluated for other runtimes so far. */
  int served() const { return served_; }

 private:
  struct Request {
    CandidateValues values;
    bool with_cost = false;
    RemoteWorkers::Done reply;
  };
  void made(const apex::GraphSnapshot& graph, int epoch);
  void dispatch();
  void scored(int copy, double fitness);
  void fail(const std::string& why);

  std::string optimizer_;
  Hooks hooks_;
  int workers_ = 1;
  std::deque<Request> waiting_;
  std::vector<std::optional<Request>> busy_;  // per copy: the request it evaluates
  std::unique_ptr<EvaluationCopies> copies_;
  std::string part_text_;  // the part the copies were made of
  bool describing_ = false;
  int epoch_ = 0;  // grows on close: what the copies of before send is ignored
  int served_ = 0;
};

}  // namespace tuning
}  // namespace apex_nodes
