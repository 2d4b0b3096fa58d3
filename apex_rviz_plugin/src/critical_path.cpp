#include "apex_rviz_plugin/critical_path.hpp"

#include <cstdio>
#include <functional>
#include <set>

namespace apex_rviz_plugin {
namespace {

double meanMs(const std::map<std::string, apex::NodeStatus>& status, const std::string& node) {
  const auto it = status.find(node);
  return it == status.end() ? 0.0 : it->second.mean_ms;
}

double latencyMs(const std::map<std::string, apex::NodeStatus>& status, const std::string& node) {
  const auto it = status.find(node);
  return it == status.end() ? -1.0 : it->second.latency_p50_ms;
}

}  // namespace

std::vector<apex::Connection> criticalPath(const apex::GraphState& graph, const std::map<std::string, apex::NodeStatus>& status,
                                           const std::string& target) {
  std::map<std::string, std::vector<const apex::Connection*>> feeding;  // node -> its data inputs' links
  for (const auto& c : graph.connections)
    if (c.kind == "data") feeding[c.to_node].push_back(&c);
  // The firing time along a node's own critical path, memoised; a cycle (not allowed for data
  // links, but a graph being edited may show one for a moment) counts a node once.
  std::map<std::string, double> cost;
  std::set<std::string> visiting;
  std::function<double(const std::string&)> along = [&](const std::string& node) -> double {
    if (auto it = cost.find(node); it != cost.end()) return it->second;
    if (!visiting.insert(node).second) return 0.0;
    double upstream = 0;
    for (const auto* c : feeding[node]) upstream = std::max(upstream, along(c->from_node));
    visiting.erase(node);
    return cost[node] = meanMs(status, node) + upstream;
  };
  std::vector<apex::Connection> path;
  std::set<std::string> seen{target};
  for (std::string node = target;;) {
    const auto& inputs = feeding[node];
    if (inputs.empty()) break;
    bool live = true;
    for (const auto* c : inputs) live = live && latencyMs(status, c->from_node) >= 0;
    const apex::Connection* last = nullptr;
    double worst = -1;
    for (const auto* c : inputs) {
      const double key = live ? latencyMs(status, c->from_node) : along(c->from_node);
      if (!last || key > worst) last = c, worst = key;
    }
    if (!seen.insert(last->from_node).second) break;  // a cycle
    path.insert(path.begin(), *last);
    node = last->from_node;
  }
  return path;
}

std::string describeCriticalPath(const std::vector<apex::Connection>& path, const std::map<std::string, apex::NodeStatus>& status,
                                 const std::string& target) {
  if (path.empty()) return target + " has no data inputs: no critical path";
  std::string text = path.front().from_node;
  double ms = meanMs(status, path.front().from_node);
  for (const auto& c : path) text += " → " + c.to_node, ms += meanMs(status, c.to_node);
  char figures[96];
  std::snprintf(figures, sizeof figures, ": %.2f ms of firing time", ms);
  text += figures;
  if (const double latency = latencyMs(status, target); latency >= 0) {
    std::snprintf(figures, sizeof figures, " (latency p50 %.1f ms)", latency);
    text += figures;
  }
  return text;
}

}  // namespace apex_rviz_plugin
