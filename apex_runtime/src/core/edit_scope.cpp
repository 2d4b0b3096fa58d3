#include "edit_scope.hpp"

namespace apex {
namespace detail {

void EditScope::pause(ThreadGroup* group) {
  if (group && paused_.insert(group).second) group->pause();
}

std::vector<NodeState*> EditScope::neighbours(NodeState* n) {
  std::vector<NodeState*> out;
  for (auto& in : n->inputs)
    if (in->edge) out.push_back(in->edge->from);
  for (auto& o : n->outputs)
    for (auto& e : o.edges) out.push_back(e->to);
  for (auto& p : n->params) {
    if (p.in_edge) out.push_back(p.in_edge->from);
    for (auto& e : p.out_edges) out.push_back(e->to);
  }
  for (auto& t : n->trigger_edges)
    for (auto& e : t) out.push_back(e->to);
  for (auto& s : n->slot_edges)
    for (auto& e : s) out.push_back(e->from);
  return out;
}

void EditScope::involve(NodeState* n) {
  if (before_.count(n)) return;
  pause(n->group);
  for (NodeState* m : neighbours(n)) pause(m->group);
  before_[n] = n->structuralBlockers();
}

void EditScope::involveWithNeighbours(NodeState* n) {
  involve(n);
  for (NodeState* m : neighbours(n)) involve(m);
}

void EditScope::added(NodeState* n) {
  pause(n->group);
  before_[n] = 0;
}

EditScope::~EditScope() {
  for (auto& [node, before] : before_) {
    const int delta = node->structuralBlockers() - before;
    // Re-check every touched node, not only those the delta made ready: a ready node
    // moved to another group, or taken off a queue, must be queued again (push is idempotent).
    if (node->readiness.correct(delta)) node->group->push(node);
  }
  for (ThreadGroup* g : paused_) g->resume();
}

}  // namespace detail
}  // namespace apex
