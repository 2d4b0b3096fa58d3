// Liveness and flushing: see live.hpp.
#include "live.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <unordered_set>

namespace apex {
namespace detail {

std::vector<NodeState*> topological(const std::vector<NodeState*>& region) {
  std::map<NodeState*, int> pending;  // inputs from inside the region not yet ordered
  for (NodeState* n : region) pending[n];
  for (NodeState* n : region)
    n->forEachDataReceiver([&](Edge& e) {
      if (auto it = pending.find(e.to); it != pending.end()) ++it->second;
    });
  std::vector<NodeState*> order;
  for (NodeState* n : region)
    if (pending[n] == 0) order.push_back(n);
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i]->forEachDataReceiver([&](Edge& e) {
      auto it = pending.find(e.to);
      if (it != pending.end() && --it->second == 0) order.push_back(e.to);
    });
  return order;  // data edges never form a cycle (connect refuses them), so this is all of region
}

namespace {

void updateLiveness(const std::vector<NodeState*>& region) {
  for (NodeState* n : topological(region)) n->updateLive();  // its senders first
}

bool hasJoin(const std::vector<NodeState*>& nodes) {
  return std::any_of(nodes.begin(), nodes.end(), [](NodeState* n) { return n->inputCount() >= 2; });
}

}  // namespace

std::vector<NodeState*> downstreamOf(const std::vector<NodeState*>& roots) {
  std::set<NodeState*> seen(roots.begin(), roots.end());
  std::vector<NodeState*> out(seen.begin(), seen.end());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i]->forEachDataReceiver([&](Edge& e) {
      if (seen.insert(e.to).second) out.push_back(e.to);
    });
  return out;
}

std::vector<NodeState*> upstreamOf(const std::vector<NodeState*>& nodes) {
  std::unordered_set<NodeState*> seen;
  std::vector<NodeState*> out;
  auto visit = [&](const std::shared_ptr<Edge>& e) {
    if (e && seen.insert(e->from).second) out.push_back(e->from);
  };
  auto expand = [&](NodeState* n) { n->forEachSender(visit); };
  for (NodeState* n : nodes) expand(n);
  for (std::size_t i = 0; i < out.size(); ++i) expand(out[i]);
  return out;
}

std::vector<NodeState*> componentOf(const std::vector<NodeState*>& roots) {
  std::set<NodeState*> seen(roots.begin(), roots.end());
  std::vector<NodeState*> out(seen.begin(), seen.end());
  auto visit = [&](NodeState* m) {
    if (seen.insert(m).second) out.push_back(m);
  };
  for (std::size_t i = 0; i < out.size(); ++i) out[i]->forEachDataOrParamNeighbour(visit);
  return out;
}

Restructure::Restructure(const std::vector<NodeState*>& targets, const std::vector<NodeState*>& others, bool flush_allowed)
    : region_(downstreamOf(targets)) {
  for (NodeState* n : region_) scope_.involve(n);
  for (NodeState* n : others) scope_.involve(n);
  if (flush_allowed && hasJoin(region_)) {
    std::vector<NodeState*> roots = region_;
    roots.insert(roots.end(), others.begin(), others.end());
    flushed_ = componentOf(roots);
    for (NodeState* n : flushed_) scope_.involve(n);
  }
}

Restructure::~Restructure() {
  updateLiveness(region_);
  for (NodeState* n : flushed_) n->flushPorts();
}

void initLiveness(NodeState* node) { node->initLive(); }

}  // namespace detail
}  // namespace apex
