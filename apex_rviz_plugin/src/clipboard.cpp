// Copy and paste: nodes as graph file text (the runtime's own format, written and
// read by apex_core), so a copy pastes into another graph, another panel, or a file.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <set>

#include "apex/core/graph_file.hpp"
#include "apex_rviz_plugin/graph_model.hpp"
#include "calls.hpp"
#include "apex/core/description.hpp"

namespace apex_rviz_plugin {
namespace {

using namespace calls;

/** The name without a trailing "_<number>": threshold_2 -> threshold. */
std::string stem(const std::string& name) {
  auto end = name.size();
  while (end > 0 && std::isdigit(static_cast<unsigned char>(name[end - 1]))) --end;
  return end > 0 && end < name.size() && name[end - 1] == '_' ? name.substr(0, end - 1) : name;
}

std::string parametersOf(const apex::NodeDescription& n) {
  std::string out;
  for (const auto& [name, value] : n.parameters) out += (out.empty() ? "" : ", ") + name + ": " + value;
  return "{" + out + "}";
}

}  // namespace

std::string GraphModel::copy(const std::vector<std::string>& names, std::string* left_out,
                             const std::map<std::string, std::pair<double, double>>& shown_at) const {
  apex::GraphDescription d;
  const std::string level = names.empty() ? "" : parentOf(names.front());
  auto rel = [&](const std::string& path) { return path.substr(level.empty() ? 0 : level.size() + 1); };
  std::set<std::string> copied;
  for (const auto& name : names) {
    const apex::NodeInfo* n = node(name);
    if (!n || parentOf(name) != level) continue;
    if (n->subgraph == "inline") {
      if (left_out) *left_out += (left_out->empty() ? "" : ", ") + name;
      continue;
    }
    apex::NodeDescription nd;
    nd.name = rel(name);
    nd.type = n->subgraph.empty() ? n->type : apex::kSubgraphType;
    nd.source = n->subgraph;
    nd.thread_group = n->thread_group.empty() ? apex::kDefaultGroup : n->thread_group;
    nd.enabled = n->enabled;
    nd.ui = n->ui;
    if (auto at = shown_at.find(name); at != shown_at.end()) nd.ui = ui(at->second.first, at->second.second);
    for (const auto& p : n->parameters) {
      nd.parameters.emplace_back(p.name, p.value);
      if (p.interactive) nd.interactive.push_back(p.name);
    }
    d.nodes.push_back(std::move(nd));
    copied.insert(name);
  }
  for (const auto& c : graph_.connections)
    if (c.kind != "export" && copied.count(c.from_node) && copied.count(c.to_node))
      d.connections.push_back({rel(c.from_node), c.from_port, rel(c.to_node), c.to_port});
  return apex::formatGraphText(d);
}

Pasted GraphModel::paste(const std::string& text, const std::string& level, double x, double y) const {
  auto parsed = apex::parseGraphText(text);
  if (!parsed) return {std::nullopt, {}, "the clipboard holds no APEX nodes: " + parsed.message()};
  const apex::GraphDescription& d = parsed.value();
  if (d.nodes.empty()) return {std::nullopt, {}, "the clipboard holds no APEX nodes"};
  Pasted out;
  double left = 1e18, top = 1e18;  // the copies' top-left corner goes to (x, y)
  for (const auto& n : d.nodes) {
    const auto [nx, ny] = positionIn(n.ui);
    left = std::min(left, nx), top = std::min(top, ny);
  }
  const double dx = x - left, dy = y - top;
  std::map<std::string, std::string> renamed;  // as copied -> as pasted (paths)
  auto free = [&](const std::string& name) {
    const std::string path = join(level, name);
    if (node(path)) return false;
    for (const auto& [from, to] : renamed)
      if (to == path) return false;
    return true;
  };
  Edit e{"", {}, {}};
  for (const auto& n : d.nodes) {
    if (n.subgraph) return {std::nullopt, {}, "'" + n.name + "' is an inline subgraph: save it to a file to paste it"};
    std::string name = n.name;
    for (int i = 1; !free(name); ++i) name = stem(n.name) + "_" + std::to_string(i);
    const std::string path = join(level, name);
    renamed[n.name] = path;
    out.names.push_back(path);
    apex::AddNode::Request add;
    add.type = n.source.empty() ? n.type : n.source;
    add.name = path, add.thread_group = n.thread_group, add.parameters = parametersOf(n);
    e.apply.push_back({"add_node", add});
    for (const auto& p : n.interactive) e.apply.push_back(interactive(path, p, true));
    if (!n.enabled) e.apply.push_back(enabled(path, false));
    const auto [x, y] = positionIn(n.ui);
    e.apply.push_back(setUi(path, ui(x + dx, y + dy)));
    e.revert.insert(e.revert.begin(), remove(path));  // its connections go with it
  }
  for (const auto& c : d.connections) {
    auto from = renamed.find(c.from_node), to = renamed.find(c.to_node);
    if (from == renamed.end() || to == renamed.end()) continue;
    apex::Connection link;
    link.from_node = from->second, link.from_port = c.from_port, link.to_node = to->second, link.to_port = c.to_port;
    e.apply.push_back(calls::connect("connect", link));
  }
  e.label = out.names.size() == 1 ? "Paste " + out.names.front() : "Paste " + std::to_string(out.names.size()) + " nodes";
  out.edit = std::move(e);
  return out;
}

Pasted GraphModel::duplicate(const std::vector<std::string>& nodes, double dx, double dy,
                             const std::map<std::string, std::pair<double, double>>& shown_at) const {
  std::string left_out;
  const std::string text = copy(nodes, &left_out, shown_at);
  double left = 1e18, top = 1e18;
  for (const auto& n : nodes) {
    const auto shown = shown_at.find(n);
    const auto [nx, ny] = shown != shown_at.end() ? shown->second : position(n);
    left = std::min(left, nx), top = std::min(top, ny);
  }
  Pasted p = paste(text, nodes.empty() ? "" : parentOf(nodes.front()), left + dx, top + dy);
  if (!left_out.empty()) p.error = left_out + " is an inline subgraph: save it to a file to copy it";
  if (p.edit) {
    p.edit->label = p.names.size() == 1 && nodes.size() == 1 ? "Duplicate " + nodes.front() + " as " + p.names.front()
                                                             : "Duplicate " + std::to_string(p.names.size()) + " nodes";
  }
  return p;
}

}  // namespace apex_rviz_plugin
