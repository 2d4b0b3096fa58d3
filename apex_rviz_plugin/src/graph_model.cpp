#include "apex_rviz_plugin/graph_model.hpp"

#include <yaml-cpp/yaml.h>

#include "apex/core/connection_rules.hpp"
#include "apex/core/node_names.hpp"
#include "apex_rviz_plugin/box_view.hpp"
#include "calls.hpp"

#include <algorithm>
#include <cctype>

namespace apex_rviz_plugin {
namespace {

using namespace calls;

/** What add_node takes to make this node again: its type, or a file-backed subgraph's file
 *  (an inline subgraph cannot be made again from the panel: add_node says so). */
std::string typeToAdd(const apex::NodeInfo& n) { return n.subgraph.empty() || n.subgraph == "inline" ? n.type : n.subgraph; }

std::string parametersText(const apex::NodeInfo& n) {
  std::string params;
  for (const auto& p : n.parameters) params += (params.empty() ? "" : ", ") + p.name + ": " + p.value;
  return "{" + params + "}";
}

/** The last ~graph, for the runtime's own connection rules (apex/core/connection_rules.hpp). */
class StateView : public apex::ConnectionView {
 public:
  explicit StateView(const apex::GraphState& graph) : graph_(graph) {}
  std::optional<apex::NodeView> node(const std::string& name) const override {
    const apex::NodeInfo* n = find(name);
    if (!n) return std::nullopt;
    apex::NodeView v;
    v.type = n->type;
    v.placeholder = n->state == "placeholder";
    for (const auto& p : n->ports) {
      apex::PortKind kind;
      if (apex::portKindFromName(p.kind, &kind)) v.ports.push_back({p.name, kind, p.type});
    }
    for (const auto& p : n->parameters) v.params.push_back(p.name);
    return v;
  }
  std::string feeding(const std::string& node, const std::string& port) const override {
    for (const auto& c : graph_.connections)
      if (c.to_node == node && c.to_port == port && !isSlot(c.to_node, c.to_port)) return c.from_node;
    return "";
  }
  bool hasEvent(const apex::ConnectionDescription& d) const override {
    for (const auto& c : graph_.connections)
      if (c.from_node == d.from_node && c.from_port == d.from_port && c.to_node == d.to_node && c.to_port == d.to_port)
        return true;
    return false;
  }
  std::vector<std::string> dataReceivers(const std::string& node) const override {
    std::vector<std::string> out;
    for (const auto& c : graph_.connections)
      if (c.from_node == node && hasPort(c.to_node, c.to_port, "input")) out.push_back(c.to_node);
    return out;
  }

 private:
  const apex::NodeInfo* find(const std::string& name) const {
    for (const auto& n : graph_.nodes)
      if (n.name == name) return &n;
    return nullptr;
  }
  bool hasPort(const std::string& node, const std::string& port, const std::string& kind) const {
    const apex::NodeInfo* n = find(node);
    if (!n) return false;
    for (const auto& p : n->ports)
      if (p.name == port && p.kind == kind) return true;
    return false;
  }
  bool isSlot(const std::string& node, const std::string& port) const { return hasPort(node, port, "slot"); }
  const apex::GraphState& graph_;
};

}  // namespace

bool GraphModel::update(const apex::GraphState& graph) {
  if (has_graph_ && graph.revision <= graph_.revision) return false;
  graph_ = graph;
  taken_ui_.clear();  // what the runtime took shows in its graph from now on
  has_graph_ = true;
  return true;
}

void GraphModel::took(const std::vector<Call>& calls) {
  for (const Call& c : calls)
    if (const auto* r = std::get_if<apex::SetUi::Request>(&c.request)) taken_ui_[r->node] = r->ui;
}

const std::string& GraphModel::uiOf(const apex::NodeInfo& n) const {
  const auto it = taken_ui_.find(n.name);
  return it == taken_ui_.end() ? n.ui : it->second;
}

const apex::NodeInfo* GraphModel::node(const std::string& name) const {
  for (const auto& n : graph_.nodes)
    if (n.name == name) return &n;
  return nullptr;
}

const apex::ParamInfo* GraphModel::parameter(const std::string& node_name, const std::string& name) const {
  const apex::NodeInfo* n = node(node_name);
  if (!n) return nullptr;
  for (const auto& p : n->parameters)
    if (p.name == name) return &p;
  return nullptr;
}

const apex::PortInfo* GraphModel::port(const std::string& node_name, const std::string& port_name,
                                       const std::string& kind) const {
  const apex::NodeInfo* n = node(node_name);
  if (!n) return nullptr;
  for (const auto& p : n->ports)
    if (p.name == port_name && (kind.empty() || p.kind == kind)) return &p;
  return nullptr;
}

std::string GraphModel::whyNot(const std::string& fn, const std::string& fp, const std::string& tn, const std::string& tp) const {
  auto checked = apex::checkConnection(StateView(graph_), {fn, fp, tn, tp, 0});
  return checked ? "" : checked.message();
}

std::string GraphModel::whyNotReplacing(const std::string& fn, const std::string& fp, const std::string& tn,
                                        const std::string& tp) const {
  const auto old = feeding(tn, tp);
  if (!old) return whyNot(fn, fp, tn, tp);
  apex::GraphState without = graph_;  // as if the link into it were gone
  auto& cs = without.connections;
  cs.erase(std::remove_if(cs.begin(), cs.end(), [&](const apex::Connection& c) { return same(c, *old); }), cs.end());
  auto checked = apex::checkConnection(StateView(without), {fn, fp, tn, tp, 0});
  return checked ? "" : checked.message();
}

std::optional<apex::Connection> GraphModel::feeding(const std::string& node_name, const std::string& port_name) const {
  const apex::PortInfo* p = port(node_name, port_name, "");
  if (!p || p->kind == "slot" || p->kind == "trigger") return std::nullopt;
  for (const auto& c : graph_.connections)
    if (c.to_node == node_name && c.to_port == port_name && c.kind != "export") return c;
  return std::nullopt;
}

std::pair<double, double> GraphModel::position(const std::string& name) const {
  const apex::NodeInfo* n = node(name);
  return n ? positionIn(n->ui) : std::pair<double, double>{0, 0};
}

std::pair<double, double> GraphModel::positionIn(const std::string& ui_text) {
  if (ui_text.empty()) return {0, 0};
  try {
    const YAML::Node u = YAML::Load(ui_text);
    if (u.IsMap()) return {u["x"] ? u["x"].as<double>() : 0.0, u["y"] ? u["y"].as<double>() : 0.0};
  } catch (const YAML::Exception&) {
  }
  return {0, 0};  // none, or metadata another front end wrote differently
}

Edit GraphModel::addNode(const std::string& type, const std::string& name, double x, double y) const {
  apex::AddNode::Request add;
  add.type = type, add.name = name;
  apex::RemoveNode::Request remove;
  remove.name = name;
  return {"Add " + name, {{"add_node", add}, setUi(name, ui(x, y))}, {{"remove_node", remove}}};
}

std::optional<Edit> GraphModel::removeNode(const std::string& name) const {
  const apex::NodeInfo* n = node(name);
  if (!n) return std::nullopt;
  apex::RemoveNode::Request remove;
  remove.name = name;
  apex::AddNode::Request add;
  add.type = typeToAdd(*n), add.name = name, add.thread_group = n->thread_group;
  add.parameters = parametersText(*n);
  Edit e{"Remove " + name, {{"remove_node", remove}}, {{"add_node", add}}};
  for (const auto& p : n->parameters) {
    apex::SetInteractive::Request i;
    i.node = name, i.parameter = p.name, i.interactive = p.interactive;
    e.revert.push_back({"set_interactive", i});
  }
  if (!n->enabled) {
    apex::SetEnabled::Request en;
    en.node = name, en.enabled = false;
    e.revert.push_back({"set_enabled", en});
  }
  if (!uiOf(*n).empty()) e.revert.push_back(setUi(name, uiOf(*n)));
  for (const auto& c : graph_.connections)
    if (c.from_node == name || c.to_node == name) e.revert.push_back(calls::connect("connect", c));
  return e;
}

Edit GraphModel::connect(const apex::Connection& c) const {
  const std::string what = c.from_node + "/" + c.from_port + " -> " + c.to_node + "/" + c.to_port;
  const auto old = feeding(c.to_node, c.to_port);
  if (!old || same(*old, c)) return {"Connect " + what, {calls::connect("connect", c)}, {calls::connect("disconnect", c)}};
  return {"Connect " + what + " (instead of " + old->from_node + "/" + old->from_port + ")",
          {calls::connect("disconnect", *old), calls::connect("connect", c)},
          {calls::connect("disconnect", c), calls::connect("connect", *old)}};
}

std::optional<Edit> GraphModel::insert(const std::string& name, const apex::Connection& c, double x, double y) const {
  const apex::NodeInfo* n = node(name);
  if (!n || c.from_node == name || c.to_node == name) return std::nullopt;
  for (const auto& k : graph_.connections)
    if (k.from_node == name || k.to_node == name) return std::nullopt;  // a node in use stays as it is
  GraphModel without;  // the graph without c: the node takes its place
  without.graph_ = graph_;
  auto& cs = without.graph_.connections;
  cs.erase(std::remove_if(cs.begin(), cs.end(), [&](const apex::Connection& k) { return same(k, c); }), cs.end());
  apex::Connection in = c, out = c;
  in.to_node = out.from_node = name;
  in.to_port = out.from_port = "";
  for (const auto& p : n->ports) {
    if (in.to_port.empty() && p.kind == "input" && without.whyNot(c.from_node, c.from_port, name, p.name).empty())
      in.to_port = p.name;
    if (out.from_port.empty() && p.kind == "output" && without.whyNot(name, p.name, c.to_node, c.to_port).empty())
      out.from_port = p.name;
  }
  if (in.to_port.empty() || out.from_port.empty()) return std::nullopt;
  Edit e("Insert " + name + " into " + c.from_node + "/" + c.from_port + " -> " + c.to_node + "/" + c.to_port, {}, {});
  e.apply = {setUi(name, withPosition(uiOf(*n), x, y)), calls::connect("disconnect", c), calls::connect("connect", in),
             calls::connect("connect", out)};
  e.revert = {calls::connect("disconnect", out), calls::connect("disconnect", in), calls::connect("connect", c),
              setUi(name, uiOf(*n).empty() ? ui(0, 0) : uiOf(*n))};
  return e;
}

Edit GraphModel::disconnect(const apex::Connection& c) const {
  return {"Disconnect " + c.from_node + "/" + c.from_port + " -> " + c.to_node + "/" + c.to_port,
          {calls::connect("disconnect", c)},
          {calls::connect("connect", c)}};
}

std::optional<Edit> GraphModel::setParameter(const std::string& node_name, const std::string& param, const std::string& value,
                                             bool dragging) const {
  const apex::ParamInfo* p = parameter(node_name, param);
  if (!p) return std::nullopt;
  apex::SetParameter::Request set, back;
  set.node = back.node = node_name;
  set.parameter = back.parameter = param;
  set.value = value;
  back.value = p->value;
  Edit e{"Set " + node_name + "/" + param, {{"set_parameter", set}}, {{"set_parameter", back}}};
  e.merge_key = "set " + node_name + "/" + param;
  e.open = dragging;
  if (p->shapes_ports)  // the new ports may lack some that are connected now: undo connects them again
    for (const auto& c : graph_.connections)
      if (c.from_node == node_name || c.to_node == node_name) {
        e.revert.push_back(calls::connect("connect", c));
        e.revert.back().if_missing = true;
      }
  return e;
}

std::optional<Edit> GraphModel::setParameters(const std::string& node_name,
                                              const std::vector<std::pair<std::string, std::string>>& values,
                                              const std::string& label) const {
  Edit all{label, {}, {}};
  for (const auto& [param, value] : values) {
    const auto e = setParameter(node_name, param, value);
    if (!e) return std::nullopt;  // all of them or none: a part of a box is no box
    all.apply.insert(all.apply.end(), e->apply.begin(), e->apply.end());
    all.revert.insert(all.revert.begin(), e->revert.begin(), e->revert.end());  // undone in reverse
  }
  if (all.apply.empty()) return std::nullopt;
  return all;
}

std::optional<Edit> GraphModel::resetToDefault(const std::string& node_name, const std::string& param) const {
  const apex::NodeInfo* n = node(node_name);
  if (!n) return std::nullopt;
  Edit all{"Reset " + node_name + (param.empty() ? "" : "/" + param) + " to default", {}, {}};
  for (const auto& p : n->parameters) {
    if ((!param.empty() && p.name != param) || p.value == p.default_value) continue;
    auto e = setParameter(node_name, p.name, p.default_value);
    all.apply.insert(all.apply.end(), e->apply.begin(), e->apply.end());
    all.revert.insert(all.revert.begin(), e->revert.begin(), e->revert.end());  // undone in reverse
  }
  if (all.apply.empty()) return std::nullopt;
  return all;
}

std::optional<Edit> GraphModel::rename(const std::string& node_name, const std::string& new_name) const {
  if (!node(node_name) || new_name.empty()) return std::nullopt;
  const auto slash = node_name.rfind('/');
  const std::string parent = slash == std::string::npos ? "" : node_name.substr(0, slash + 1);
  apex::RenameNode::Request to, back;
  to.name = node_name, to.new_name = new_name;
  back.name = parent + new_name, back.new_name = node_name.substr(parent.size());
  return Edit{"Rename " + node_name + " to " + new_name, {{"rename_node", to}}, {{"rename_node", back}}};
}

bool GraphModel::hasPosition(const std::string& name) const {
  const apex::NodeInfo* n = node(name);
  if (!n || n->ui.empty()) return false;
  try {
    const YAML::Node u = YAML::Load(n->ui);
    return u.IsMap() && u["x"] && u["y"];
  } catch (const YAML::Exception&) {
    return false;
  }
}

std::optional<Edit> GraphModel::arrange(const std::map<std::string, std::pair<double, double>>& positions,
                                        const std::string& label,
                                        const std::map<std::string, std::pair<double, double>>& shown) const {
  Edit e(label, {}, {});
  for (const auto& [name, at] : positions) {
    const apex::NodeInfo* n = node(name);
    if (!n) continue;
    e.apply.push_back(setUi(name, withPosition(uiOf(*n), at.first, at.second)));
    const auto was = shown.find(name);
    if (was != shown.end()) e.revert.push_back(setUi(name, withPosition(uiOf(*n), was->second.first, was->second.second)));
    else e.revert.push_back(setUi(name, uiOf(*n).empty() ? ui(0, 0) : uiOf(*n)));
  }
  if (e.apply.empty()) return std::nullopt;
  return e;
}

std::optional<Edit> GraphModel::move(const std::string& node_name, double x, double y) const {
  const apex::NodeInfo* n = node(node_name);
  if (!n) return std::nullopt;
  return Edit{"Move " + node_name,
              {setUi(node_name, withPosition(uiOf(*n), x, y))},
              {setUi(node_name, uiOf(*n).empty() ? ui(0, 0) : uiOf(*n))}};
}

std::optional<Edit> GraphModel::setExpanded(const std::string& node_name, bool expanded) const {
  const apex::NodeInfo* n = node(node_name);
  if (!n) return std::nullopt;
  return Edit{(expanded ? "Expand " : "Collapse ") + node_name,
              {setUi(node_name, withUiKey(uiOf(*n), "expanded", expanded ? "true" : "false"))},
              {setUi(node_name, uiOf(*n).empty() ? ui(0, 0) : uiOf(*n))}};
}

std::optional<Edit> GraphModel::setPinned(const std::string& node_name, const std::string& param, bool pinned) const {
  const apex::NodeInfo* n = node(node_name);
  if (!n || !parameter(node_name, param)) return std::nullopt;
  std::vector<std::string> now = BoxView::of(uiOf(*n)).pinned;
  now.erase(std::remove(now.begin(), now.end(), param), now.end());
  if (pinned) now.push_back(param);
  std::string list = "[";
  for (const auto& p : now) list += (list.size() > 1 ? ", " : "") + p;
  return Edit{(pinned ? "Pin " : "Unpin ") + node_name + "/" + param,
              {setUi(node_name, withUiKey(uiOf(*n), "pinned", list + "]"))},
              {setUi(node_name, uiOf(*n).empty() ? ui(0, 0) : uiOf(*n))}};
}

std::string GraphModel::freshName(const std::string& type, const std::string& parent,
                                  const std::set<std::string>& reserved) const {
  const std::string base = apex::nodeBaseName(type);  // the runtime's rule
  for (int i = 1;; ++i) {
    std::string name = base + "_" + std::to_string(i);
    const std::string path = join(parent, name);
    if (!node(path) && !reserved.count(path)) return name;
  }
}

std::optional<Edit> GraphModel::group(const std::vector<std::string>& nodes) const {
  if (nodes.empty()) return std::nullopt;
  const std::string parent = parentOf(nodes.front());
  std::string name;
  for (int i = 1; name.empty() || node(join(parent, name)); ++i) name = "subgraph_" + std::to_string(i);
  apex::Group::Request g;
  g.nodes = nodes, g.name = name;
  apex::Ungroup::Request u;
  u.name = join(parent, name);
  return Edit{"Group into " + name, {{"group", g}}, {{"ungroup", u}}};
}

std::optional<Edit> GraphModel::ungroup(const std::string& path) const {
  const apex::NodeInfo* n = node(path);
  if (!n || n->subgraph.empty()) return std::nullopt;
  const std::string parent = parentOf(path);
  apex::Group::Request g;  // its nodes, as they will be named beside it; back as it was
  g.name = path.substr(parent.empty() ? 0 : parent.size() + 1);
  g.restore = true;
  for (const auto& m : graph_.nodes)
    if (parentOf(m.name) == path) g.nodes.push_back(join(parent, m.name.substr(path.size() + 1)));
  apex::Ungroup::Request u;
  u.name = path;
  return Edit{"Ungroup " + g.name, {{"ungroup", u}}, {{"group", g}}};
}

std::optional<Edit> GraphModel::setEnabled(const std::string& name, bool enabled) const {
  const apex::NodeInfo* n = node(name);
  if (!n) return std::nullopt;
  apex::SetEnabled::Request set, back;
  set.node = back.node = name;
  set.enabled = enabled, back.enabled = n->enabled;
  return Edit{(enabled ? "Enable " : "Disable ") + name, {{"set_enabled", set}}, {{"set_enabled", back}}};
}

std::optional<Edit> GraphModel::setThreadGroup(const std::string& name, const std::string& group) const {
  const apex::NodeInfo* n = node(name);
  if (!n) return std::nullopt;
  apex::SetThreadGroup::Request set, back;
  set.node = back.node = name;
  set.group = group, back.group = n->thread_group;
  return Edit{"Move " + name + " to group " + group, {{"set_thread_group", set}}, {{"set_thread_group", back}}};
}

std::optional<Edit> GraphModel::setThreadGroups(const std::vector<std::pair<std::string, std::string>>& moves,
                                                const std::string& label) const {
  Edit e(label, {}, {});
  for (const auto& [name, group] : moves) {
    const apex::NodeInfo* n = node(name);
    if (!n || n->thread_group == group) continue;
    apex::SetThreadGroup::Request set, back;
    set.node = back.node = name;
    set.group = group, back.group = n->thread_group;
    e.apply.push_back({"set_thread_group", set});
    e.revert.insert(e.revert.begin(), Call{"set_thread_group", back});  // the last moved goes back first
  }
  if (e.apply.empty()) return std::nullopt;
  return e;
}

std::optional<Edit> GraphModel::setInteractive(const std::string& name, const std::string& param, bool interactive) const {
  const apex::ParamInfo* p = parameter(name, param);
  if (!p) return std::nullopt;
  apex::SetInteractive::Request set, back;
  set.node = back.node = name;
  set.parameter = back.parameter = param;
  set.interactive = interactive, back.interactive = p->interactive;
  Edit e{(interactive ? "Show ports of " : "Hide ports of ") + name + "/" + param,
         {{"set_interactive", set}},
         {{"set_interactive", back}}};
  if (!interactive)  // hiding the ports drops their connections: undo restores them
    for (const auto& c : graph_.connections)
      if ((c.from_node == name && c.from_port == param) || (c.to_node == name && c.to_port == param))
        e.revert.push_back(calls::connect("connect", c));
  return e;
}

void EditHistory::done(Edit edit) {
  redo_.clear();
  if (!undo_.empty() && undo_.back().open && !edit.merge_key.empty() && undo_.back().merge_key == edit.merge_key) {
    Edit& gesture = undo_.back();  // its revert goes back to before the gesture
    gesture.apply = std::move(edit.apply);
    gesture.open = edit.open;
    return;
  }
  if (!undo_.empty()) undo_.back().open = false;  // another edit ends a gesture
  undo_.push_back(std::move(edit));
}

std::vector<Call> EditHistory::undo() {
  if (undo_.empty()) return {};
  redo_.push_back(std::move(undo_.back()));
  undo_.pop_back();
  redo_.back().open = false;  // a gesture undone is over
  return redo_.back().revert;
}

std::vector<Call> EditHistory::redo() {
  if (redo_.empty()) return {};
  undo_.push_back(std::move(redo_.back()));
  redo_.pop_back();
  return undo_.back().apply;
}

}  // namespace apex_rviz_plugin
