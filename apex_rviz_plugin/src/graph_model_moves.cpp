// GraphModel::moves: where a rename, a group or an ungroup takes nodes, for who follows nodes
// by name (rviz displays, inspected ports), read off the calls before they are sent.
#include "apex_rviz_plugin/graph_model.hpp"

#include "calls.hpp"

#include <variant>

namespace apex_rviz_plugin {

std::vector<std::pair<std::string, std::string>> GraphModel::moves(const std::vector<Call>& calls) const {
  using calls::join;
  using calls::parentOf;
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& c : calls) {
    if (const auto* r = std::get_if<apex::RenameNode::Request>(&c.request)) {  // it stays in its subgraph
      out.emplace_back(r->name, join(parentOf(r->name), r->new_name));
    } else if (const auto* g = std::get_if<apex::Group::Request>(&c.request); g && !g->nodes.empty()) {
      const std::string parent = parentOf(g->nodes.front()), path = join(parent, g->name);
      for (const auto& n : g->nodes) out.emplace_back(n, join(path, n.substr(parent.empty() ? 0 : parent.size() + 1)));
    } else if (const auto* u = std::get_if<apex::Ungroup::Request>(&c.request)) {  // its nodes up beside it
      for (const auto& n : graph_.nodes)
        if (parentOf(n.name) == u->name) out.emplace_back(n.name, join(parentOf(u->name), n.name.substr(u->name.size() + 1)));
    }
  }
  return out;
}

bool GraphModel::regroups(const std::vector<Call>& calls) {
  for (const auto& c : calls)
    if (std::holds_alternative<apex::Group::Request>(c.request) || std::holds_alternative<apex::Ungroup::Request>(c.request))
      return true;
  return false;
}

}  // namespace apex_rviz_plugin
