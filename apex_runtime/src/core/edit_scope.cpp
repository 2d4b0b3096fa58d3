#include "edit_scope.hpp"

namespace apex {
namespace detail {

void EditScope::pause(ThreadGroup* group) {
  if (group && paused_.insert(group).second) group->pause();
}

std::vector<NodeState*> EditScope::neighbours(NodeState* n) {
  std::vector<NodeState*> out;
  n->forEachNeighbour([&](NodeState* m) { out.push_back(m); });
  return out;
}

void EditScope::involve(NodeState* n) {
  if (before_.count(n)) return;
  pause(n->group());
  for (NodeState* m : neighbours(n)) pause(m->group());
  before_[n] = n->structuralBlockers();
}

void EditScope::involveWithNeighbours(NodeState* n) {
  involve(n);
  for (NodeState* m : neighbours(n)) involve(m);
}

void EditScope::added(NodeState* n) {
  pause(n->group());
  before_[n] = 0;
}

EditScope::~EditScope() {
  for (auto& [node, before] : before_) {
    node->correctBlockers(node->structuralBlockers() - before);
  }
  for (ThreadGroup* g : paused_) g->resume();
}

}  // namespace detail
}  // namespace apex
