// Liveness and frame alignment across edits (docs/architecture.md, "Edits that
// cannot stall"). A node is live when a source reaches it: only live inputs are
// waited for, so a part cut off by an edit holds no other path hostage. An edit
// that changes what a join (a node with several inputs) receives first drops
// every message in flight in its connected part: afterwards every path of every
// fork starts from the same next frame, so a join never pairs two frames.
#pragma once

#include <vector>

#include "edit_scope.hpp"
#include "node_state.hpp"

namespace apex {
namespace detail {

/** @brief The nodes data reaches from `roots` (roots included), over edges into data inputs. */
std::vector<NodeState*> downstreamOf(const std::vector<NodeState*>& roots);
/** @brief The nodes whose data or parameter values reach any of `nodes` (a node of `nodes` only
 *  if another reaches it), each once. */
std::vector<NodeState*> upstreamOf(const std::vector<NodeState*>& nodes);
/** @brief Every node joined to `roots` by data or parameter connections (events excluded). */
std::vector<NodeState*> componentOf(const std::vector<NodeState*>& roots);

/** @brief One edit that changes which data inputs are connected.
 *
 *  Built before the edit with the nodes whose inputs change (`targets`) and the
 *  other nodes the edit touches (`others`): pauses the groups of everything
 *  that may change. Destroyed after the edit: recomputes liveness downstream of
 *  the targets and, when a join is downstream and the graph has run, flushes the
 *  connected part. The EditScope then corrects each node's blockers (readiness.hpp). */
class Restructure {
 public:
  Restructure(const std::vector<NodeState*>& targets, const std::vector<NodeState*>& others, bool flush_allowed);
  ~Restructure();
  Restructure(const Restructure&) = delete;
  Restructure& operator=(const Restructure&) = delete;
  EditScope& scope() { return scope_; }

 private:
  EditScope scope_;  // destroyed last: after liveness and flush
  std::vector<NodeState*> region_;
  std::vector<NodeState*> flushed_;
};

/** @brief `nodes` in an order where every node comes after those feeding its data inputs. */
std::vector<NodeState*> topological(const std::vector<NodeState*>& nodes);

/** @brief Sets the liveness of a node with no connections yet (a new node). */
void initLiveness(NodeState* node);

}  // namespace detail
}  // namespace apex
