// An edit's critical section: pauses the thread groups of the nodes it touches
// and of their neighbours, and afterwards corrects each touched node's
// blockers (readiness.hpp) by how much its structural part changed (has_data and other
// atomic changes made meanwhile by other threads stay counted).
#pragma once

#include <map>
#include <set>
#include <vector>

#include "node_state.hpp"

namespace apex {
namespace detail {

class EditScope {
 public:
  EditScope() = default;
  EditScope(const EditScope&) = delete;
  EditScope& operator=(const EditScope&) = delete;
  ~EditScope();

  /** The node's counts may change: pause it and its neighbours, remember its count. */
  void involve(NodeState* node);
  /** Involve the node and every node connected to it. */
  void involveWithNeighbours(NodeState* node);
  /** A new node: its count starts at zero. */
  void added(NodeState* node);
  /** A removed node: do not count it afterwards. */
  void forget(NodeState* node) { before_.erase(node); }
  void pause(ThreadGroup* group);

  static std::vector<NodeState*> neighbours(NodeState* node);

 private:
  std::map<NodeState*, int> before_;
  std::set<ThreadGroup*> paused_;
};

}  // namespace detail
}  // namespace apex
