// Subgraphs: adding one (its nodes, connections and exports), what its ports
// stand for, its façade interface, and nesting the flat graph back into
// subgraphs to describe or save it. See subgraph.hpp for the model.
#include <algorithm>
#include <array>
#include <map>
#include <set>

#include "apex/core/graph.hpp"
#include "apex/core/limits.hpp"
#include "apex/core/graph_file.hpp"
#include "edit_scope.hpp"
#include "names.hpp"
#include "node_state.hpp"
#include "subgraph.hpp"

namespace apex {

using detail::join;
using detail::NodeState;
using detail::parentOf;
using detail::splitEnd;
using detail::Subgraph;
using Kind = ExportDescription::Kind;

namespace {

const char* kindName(Kind k) {
  switch (k) {
    case Kind::Input: return "input";
    case Kind::Output: return "output";
    case Kind::Parameter: return "parameter";
    case Kind::Slot: return "slot";
    case Kind::Trigger: return "trigger";
  }
  return "";
}

std::string listExports(const Subgraph& sg, bool (*side)(Kind)) {
  std::string s;
  for (const auto& e : sg.exports)
    if (side(e.kind)) s += (s.empty() ? "" : ", ") + e.name + " (" + kindName(e.kind) + ")";
  return s.empty() ? "none" : s;
}

/** The node at a path relative to `g`, looking into inline and file-backed subgraphs. */
NodeDescription* findIn(GraphDescription& g, const std::string& path) {
  const auto slash = path.find('/');
  const std::string head = path.substr(0, slash);
  for (auto& n : g.nodes) {
    if (n.name != head) continue;
    if (slash == std::string::npos) return &n;
    if (!n.subgraph) return nullptr;
    auto inner = std::make_shared<GraphDescription>(*n.subgraph);  // copy on write
    n.subgraph = inner;
    return findIn(*inner, path.substr(slash + 1));
  }
  return nullptr;
}

/** Leaves out an exported parameter "node/param" of `g`: its value and its ports, down through
 *  the subgraphs it is exported from. */
void mask(GraphDescription& g, const std::string& endpoint) {
  auto [node, param] = splitEnd(endpoint);
  NodeDescription* n = findIn(g, node);
  if (!n) return;
  for (auto& [name, text] : n->parameters) if (name == param) text = "~";
  n->interactive.erase(std::remove(n->interactive.begin(), n->interactive.end(), param), n->interactive.end());
  if (!n->subgraph) return;
  auto inner = std::make_shared<GraphDescription>(*n->subgraph);
  n->subgraph = inner;
  for (const auto& e : inner->exports)
    if (e.kind == Kind::Parameter && e.name == param) mask(*inner, e.inner.front());
}

/** The inner graph's canonical text with its exported parameters left out: what a
 *  file-backed subgraph is compared by. */
std::string maskedText(const GraphDescription& inner, const std::vector<ExportDescription>& exports) {
  GraphDescription g = inner;
  for (const auto& e : exports)
    if (e.kind == Kind::Parameter) mask(g, e.inner.front());
  return formatGraphText(g);
}

/** Inner-first: a file-backed subgraph whose inner graph no longer reads as its file made it
 *  is described inline, so that saving keeps the edit. */
void markEdited(GraphDescription& g, const std::map<std::string, std::shared_ptr<Subgraph>>& subgraphs,
                const std::string& prefix) {
  for (auto& n : g.nodes) {
    if (!n.subgraph) continue;
    const std::string path = join(prefix, n.name);
    auto inner = std::make_shared<GraphDescription>(*n.subgraph);
    markEdited(*inner, subgraphs, path);
    n.subgraph = inner;
    auto sg = subgraphs.find(path);
    if (!n.source.empty() && sg != subgraphs.end() && maskedText(*inner, sg->second->exports) != sg->second->baseline)
      n.source.clear();
  }
}

}  // namespace

const NodeDescription* findNode(const GraphDescription& graph, const std::string& path) {
  const auto slash = path.find('/');
  const std::string head = path.substr(0, slash);
  for (const auto& n : graph.nodes) {
    if (n.name != head) continue;
    if (slash == std::string::npos) return &n;
    return n.subgraph ? findNode(*n.subgraph, path.substr(slash + 1)) : nullptr;
  }
  return nullptr;
}

std::shared_ptr<Subgraph> Graph::subgraph(const std::string& path) const {
  auto it = subgraphs_.find(path);
  return it == subgraphs_.end() ? nullptr : it->second;
}

std::string Graph::checkNewPath(const std::string& path) const {
  std::size_t start = 0;
  while (true) {
    const auto slash = path.find('/', start);
    if (!validName(path.substr(start, slash - start)))
      return "node name '" + path + "' " + kNameRule + (path.find('/') == std::string::npos ? "" : " (in each part of a path a/b)");
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  if (nodes_.count(path) || subgraphs_.count(path)) return "a node named '" + path + "' already exists";
  const std::string parent = parentOf(path);
  if (!parent.empty() && !subgraphs_.count(parent))
    return "node name '" + path + "': there is no subgraph '" + parent + "' to put it in";
  return "";
}

std::vector<std::string> Graph::nodesUnder(const std::string& path) const {
  std::vector<std::string> out;
  if (path.empty()) {  // the whole graph
    for (const auto& [name, n] : nodes_) out.push_back(name);
    return out;
  }
  const std::string prefix = path + "/";
  for (auto it = nodes_.lower_bound(prefix); it != nodes_.end() && it->first.compare(0, prefix.size(), prefix) == 0; ++it)
    out.push_back(it->first);
  return out;
}

// ------------------------------------------------------------------ what a port stands for

Result<std::pair<std::string, std::string>> Graph::sender(const std::string& node, const std::string& port) const {
  auto sg = subgraph(node);
  if (!sg) return std::make_pair(node, port);
  for (const auto& e : sg->exports) {
    if (e.name != port || !detail::sendingExport(e.kind)) continue;
    auto [n, p] = splitEnd(e.inner.front());
    return sender(join(node, n), p);
  }
  return Status::error("subgraph '" + node + "' exports no output, trigger or parameter '" + port +
                       "' (it exports: " + listExports(*sg, detail::sendingExport) + ")");
}

Result<std::vector<std::pair<std::string, std::string>>> Graph::receivers(const std::string& node,
                                                                         const std::string& port) const {
  std::vector<std::pair<std::string, std::string>> out;
  auto sg = subgraph(node);
  if (!sg) {
    out.emplace_back(node, port);
    return out;
  }
  for (const auto& e : sg->exports) {
    if (e.name != port || !detail::receivingExport(e.kind)) continue;
    for (const auto& inner : e.inner) {
      auto [n, p] = splitEnd(inner);
      auto more = receivers(join(node, n), p);
      if (!more) return more;
      out.insert(out.end(), more.value().begin(), more.value().end());
    }
    return out;
  }
  return Status::error("subgraph '" + node + "' exports no input, slot or parameter '" + port +
                       "' (it exports: " + listExports(*sg, detail::receivingExport) + ")");
}

Result<std::pair<std::string, std::string>> Graph::exportedParam(const std::string& node, const std::string& param) const {
  auto sg = subgraph(node);
  if (!sg) return std::make_pair(node, param);
  for (const auto& e : sg->exports) {
    if (e.name != param || e.kind != Kind::Parameter) continue;
    auto [n, p] = splitEnd(e.inner.front());
    return exportedParam(join(node, n), p);
  }
  std::string list;
  for (const auto& e : sg->exports) if (e.kind == Kind::Parameter) list += (list.empty() ? "" : ", ") + e.name;
  return Status::error("subgraph '" + node + "' exports no parameter '" + param + "' (parameters: " +
                       (list.empty() ? "none" : list) + ")");
}

// ------------------------------------------------------------------ adding

Status Graph::checkExports(const Subgraph& sg) const {
  std::set<std::pair<bool, std::string>> seen;  // (sending side, name)
  for (const auto& e : sg.exports) {
    const std::string what = (e.line ? "line " + std::to_string(e.line) + ": " : "") + "export '" + e.name + "'";
    if (!validName(e.name)) return Status::error(what + ": the name " + kNameRule);
    if (detail::sendingExport(e.kind) && !seen.insert({true, e.name}).second)
      return Status::error(what + ": the name is exported twice as an output, trigger or parameter");
    if (detail::receivingExport(e.kind) && e.kind != Kind::Parameter && !seen.insert({false, e.name}).second)
      return Status::error(what + ": the name is exported twice as an input or slot");
    for (const auto& inner : e.inner) {
      const auto split = splitEnd(inner);
      const std::string rel = split.first, port = split.second;
      const std::string path = join(sg.path, rel);
      const std::string says = what + " stands for '" + inner + "', but ";
      if (auto nested = subgraph(path)) {
        auto found = detail::sendingExport(e.kind) ? sender(path, port).status()
                                                   : receivers(path, port).status();
        if (!found) return Status::error(says + found.message());
        continue;
      }
      auto n = find(path);
      if (!n) return Status::error(says + "there is no node '" + rel + "' in it");
      if (!n->type) continue;  // a placeholder: its ports are unknown
      const Manifest& m = n->manifest();
      const bool has = [&] {
        switch (e.kind) {
          case Kind::Input: return m.findInput(port) || m.findParam(port);
          case Kind::Output: return m.findOutput(port) || m.findParam(port);
          case Kind::Parameter: return m.findParam(port) != nullptr;
          case Kind::Slot: return m.findSlot(port) != nullptr;
          case Kind::Trigger: return m.findTrigger(port) != nullptr;
        }
        return false;
      }();
      if (!has)
        return Status::error(says + "node '" + path + "' (" + n->typeId() + ") has no " + kindName(e.kind) + " '" +
                             port + "'");
    }
  }
  return Status::ok();
}

Result<std::string> Graph::addSubgraph(const NodeDescription& d) {
  const std::string from = d.source.empty() ? "" : " ('" + d.source + "')";
  if (!d.subgraph)
    return Status::error("subgraph '" + d.name + "'" + from + " was not read: subgraph files are read with the graph file");
  auto sg = std::make_shared<Subgraph>();
  {
    auto lock = lockEdits();
    if (auto why = checkNewPath(d.name); !why.empty()) return Status::error(why);
    std::set<std::string> more;  // the limit counts the groups it would add, together
    for (const auto& g : d.subgraph->thread_groups) {
      if (!validName(g)) return Status::error("subgraph '" + d.name + "': thread group name '" + g + "' " + kNameRule);
      if (!groups_.count(g)) more.insert(g);
    }
    if (groups_.size() + more.size() > kMaxGraphGroups)
      return Status::error("subgraph '" + d.name + "': its " + std::to_string(more.size()) + " new thread groups would " +
                           "pass the limit of " + std::to_string(kMaxGraphGroups) + " (the graph has " +
                           std::to_string(groups_.size()) + ")");
    sg->path = d.name;
    sg->source = d.source;
    sg->seq = next_seq_++;
    sg->thread_groups = d.subgraph->thread_groups;
    sg->exports = d.subgraph->exports;
    sg->ui = d.ui;
    for (const auto& g : sg->thread_groups) group(g);
    subgraphs_[d.name] = sg;
    bump();
  }
  auto undo = [&](int line, const std::string& why) {
    (void)removeNode(d.name);
    return Status::error("subgraph '" + d.name + "'" + from + ": " + (line ? "line " + std::to_string(line) + ": " : "") + why);
  };
  LoadReport ignored;
  for (const auto& inner : d.subgraph->nodes) {
    NodeDescription named = inner;
    named.name = join(d.name, inner.name);
    named.line = 0;  // the line is named here, with the subgraph
    if (auto st = applyNode(named, ignored); !st) return undo(inner.line, st.message());
  }
  for (const auto& c : d.subgraph->connections) {
    auto lock = lockEdits();
    if (auto st = connectLocked({join(d.name, c.from_node), c.from_port, join(d.name, c.to_node), c.to_port, 0}); !st) {
      lock.unlock();
      return undo(c.line, st.message());
    }
  }
  {
    auto lock = lockEdits();
    if (auto st = checkExports(*sg); !st) {
      lock.unlock();
      return undo(0, st.message());
    }
    for (const auto& e : sg->exports) {
      if (e.kind != Kind::Parameter) continue;
      auto real = exportedParam(d.name, e.name);
      auto n = real ? find(real.value().first) : nullptr;
      const int i = n && n->type ? n->findParam(real.value().second) : -1;
      if (i < 0) continue;
      std::lock_guard<std::mutex> g(n->state_mutex);
      sg->defaults[e.name] = toText(n->params[i].requested);
    }
    const GraphDescription now = describeLocked();
    if (const NodeDescription* self = findNode(now, d.name)) sg->baseline = maskedText(*self->subgraph, sg->exports);
  }
  for (const auto& [param, text] : d.parameters)
    if (auto r = setParameter(d.name, param, text); !r) return undo(d.line, r.message());
  for (const auto& param : d.interactive)
    if (auto st = setInteractive(d.name, param, true); !st) return undo(d.line, st.message());
  if (!d.enabled) (void)setEnabled(d.name, false);
  return d.name;
}

// ------------------------------------------------------------------ removing, enabling

void Graph::removeSubgraphLocked(const std::string& path) {
  for (const auto& name : nodesUnder(path)) {
    auto n = find(name);
    retire(n.get());
    order_.erase(n->seq);
    nodes_.erase(name);
  }
  const std::string prefix = path + "/";
  for (auto it = subgraphs_.begin(); it != subgraphs_.end();)
    it = it->first == path || it->first.compare(0, prefix.size(), prefix) == 0 ? subgraphs_.erase(it) : std::next(it);
  dormant_.erase(std::remove_if(dormant_.begin(), dormant_.end(),
                                [&](const auto& c) {
                                  return c.from_node.compare(0, prefix.size(), prefix) == 0 ||
                                         c.to_node.compare(0, prefix.size(), prefix) == 0;
                                }),
                 dormant_.end());
}

void Graph::dropExportsOf(const std::string& node) {
  for (std::string parent = parentOf(node), rel = node.substr(node.rfind('/') + 1); !parent.empty();
       rel = parent.substr(parent.rfind('/') + 1) + "/" + rel, parent = parentOf(parent)) {
    auto sg = subgraph(parent);
    if (!sg) continue;
    for (auto& e : sg->exports)
      e.inner.erase(std::remove_if(e.inner.begin(), e.inner.end(),
                                   [&](const std::string& i) { return splitEnd(i).first == rel; }),
                    e.inner.end());
    sg->exports.erase(std::remove_if(sg->exports.begin(), sg->exports.end(), [](const auto& e) { return e.inner.empty(); }),
                      sg->exports.end());
  }
}

void Graph::applyOuterEnabled(const std::string& path) {
  for (const auto& name : nodesUnder(path)) {
    bool outer = true;
    for (std::string p = parentOf(name); !p.empty(); p = parentOf(p))
      if (auto sg = subgraph(p)) outer = outer && sg->enabled;
    NodeState& n = *find(name);
    {
      std::lock_guard<std::mutex> g(n.state_mutex);
      n.outer_enabled = outer;
    }
    if (n.type) n.post([](NodeState& x) { x.applyEnabled(); });
    changedDownstreamOf(&n);
  }
}

// ------------------------------------------------------------------ grouping

namespace {
std::string unique(std::set<std::string>& taken, const std::string& node, const std::string& port) {
  std::string name = port;
  if (taken.count(name)) name = node.substr(node.rfind('/') + 1) + "_" + port;
  for (int i = 2; taken.count(name); ++i) name = port + "_" + std::to_string(i);
  taken.insert(name);
  return name;
}
}  // namespace

std::shared_ptr<detail::Subgraph> Graph::takeUngrouped(const std::string& path, const std::vector<std::string>& members) {
  auto it = ungrouped_.find(path);
  if (it == ungrouped_.end()) return nullptr;
  auto [sg, had] = std::move(it->second);
  ungrouped_.erase(it);
  return std::set<std::string>(members.begin(), members.end()) == had ? sg : nullptr;
}

Status Graph::group(const std::vector<std::string>& members, const std::string& name, bool restore) {
  auto lock = lockEdits();
  auto fail = [&](const std::string& why) { return Status::error("cannot group into '" + name + "': " + why); };
  if (members.empty()) return fail("no nodes given");
  const std::string parent = parentOf(members.front());
  std::set<std::string> seen;
  for (const auto& m : members) {
    if (!find(m) && !subgraph(m)) return fail("no node named '" + m + "'");
    if (parentOf(m) != parent)
      return fail("'" + m + "' and '" + members.front() + "' are not beside each other (group nodes of one level)");
    if (!seen.insert(m).second) return fail("'" + m + "' is named twice");
  }
  const std::string path = join(parent, name);
  if (auto why = checkNewPath(path); !why.empty()) return fail(why);
  auto inside = [&](const std::string& node) {
    for (const auto& m : members)
      if (node == m || node.compare(0, m.size() + 1, m + "/") == 0) return true;
    return false;
  };
  auto rel = [&](const std::string& node, const std::string& port) {
    return node.substr(parent.empty() ? 0 : parent.size() + 1) + "/" + port;
  };
  std::shared_ptr<Subgraph> before = restore ? takeUngrouped(path, members) : nullptr;
  // Each crossing connection through an export: one per outside sender (it may feed several
  // inner receivers), one per inner sender (it may feed several outside).
  auto sg = std::make_shared<Subgraph>();
  std::set<std::string> sending, receiving;
  std::map<std::string, std::size_t> by_sender;  // "node/port" → index in exports
  auto cross = [&](const std::string& from, const std::string& from_port, const std::string& to,
                   const std::string& to_port, bool event) {
    if (inside(from) == inside(to)) return;
    const std::string key = from + "/" + from_port;
    auto it = by_sender.find(key);
    if (it != by_sender.end()) {
      auto& e = sg->exports[it->second];
      if (inside(to)) e.inner.push_back(rel(to, to_port));
      return;
    }
    ExportDescription e;
    if (inside(to)) {
      e.kind = event ? Kind::Slot : Kind::Input;
      e.name = unique(receiving, to, to_port);
      e.inner = {rel(to, to_port)};
    } else {
      e.kind = event ? Kind::Trigger : Kind::Output;
      e.name = unique(sending, from, from_port);
      e.inner = {rel(from, from_port)};
    }
    by_sender[key] = sg->exports.size();
    sg->exports.push_back(std::move(e));
  };
  for (auto& [seq, n] : order_) {
    const Manifest& m = n->manifest();
    auto target = [](const detail::Edge& e) {
      return e.to_param ? e.to->manifest().params[e.to_index].name : e.to->manifest().inputs[e.to_index].name;
    };
    if (!n->type) continue;
    for (std::size_t i = 0; i < n->outputs.size(); ++i)
      for (auto& e : n->outputs[i].edges) cross(n->name, m.outputs[i].name, e->to->name, target(*e), false);
    for (std::size_t i = 0; i < n->params.size(); ++i)
      for (auto& e : n->params[i].out_edges) cross(n->name, m.params[i].name, e->to->name, target(*e), false);
    for (std::size_t i = 0; i < n->trigger_edges.size(); ++i)
      for (auto& e : n->trigger_edges[i])
        cross(n->name, m.triggers[i].name, e->to->name, e->to->manifest().slots[e->slot].name, true);
  }
  sg->path = path;
  sg->seq = ~0ull;  // before the first of its nodes, where it stands in the order
  for (const auto& m : members) {
    if (auto n = find(m)) sg->seq = std::min(sg->seq, n->seq);
    if (auto s = subgraph(m)) sg->seq = std::min(sg->seq, s->seq);
    for (const auto& under : nodesUnder(m)) sg->seq = std::min(sg->seq, find(under)->seq);
  }
  if (auto first = find(members.front())) {
    std::lock_guard<std::mutex> g(first->state_mutex);
    sg->ui = first->ui;
  } else {
    sg->ui = subgraph(members.front())->ui;
  }
  subgraphs_[path] = sg;
  for (const auto& m : members) moveLocked(m, join(path, m.substr(parent.empty() ? 0 : parent.size() + 1)));
  if (before && checkExports(*before)) {  // as it was; its exports cover what crosses, as they did
    before->seq = sg->seq;
    subgraphs_[path] = before;
    if (!before->enabled) applyOuterEnabled(path);
  }
  bump();
  return Status::ok();
}

Status Graph::ungroup(const std::string& path) {
  auto lock = lockEdits();
  auto sg = subgraph(path);
  if (!sg) return Status::error("cannot ungroup '" + path + "': " + (find(path) ? "it is not a subgraph" : "no node named '" + path + "'"));
  const std::string parent = parentOf(path);
  std::vector<std::string> children;
  for (const auto& [name, n] : nodes_) if (parentOf(name) == path) children.push_back(name);
  for (const auto& [name, s] : subgraphs_) if (parentOf(name) == path) children.push_back(name);
  for (const auto& c : children) {
    const std::string to = join(parent, c.substr(path.size() + 1));
    if (to != path && (find(to) || subgraph(to)))
      return Status::error("cannot ungroup '" + path + "': its node '" + c.substr(path.size() + 1) +
                           "' would take the name of the node '" + to + "' beside it (rename one first)");
  }
  if (auto around = subgraph(parent)) {  // its exports that stood for this one's: for what those stood for
    const std::string self = path.substr(parent.size() + 1);
    for (auto& e : around->exports) {
      std::vector<std::string> inner;
      for (const auto& i : e.inner) {
        auto [node, port] = splitEnd(i);
        if (node != self) {
          inner.push_back(i);
          continue;
        }
        for (const auto& x : sg->exports)
          if (x.name == port && (detail::sendingExport(e.kind) ? detail::sendingExport(x.kind) : detail::receivingExport(x.kind)))
            inner.insert(inner.end(), x.inner.begin(), x.inner.end());
      }
      e.inner = std::move(inner);
    }
  }
  subgraphs_.erase(path);
  for (const auto& c : children) moveLocked(c, join(parent, c.substr(path.size() + 1)));
  std::set<std::string> moved;
  for (const auto& c : children) moved.insert(join(parent, c.substr(path.size() + 1)));
  ungrouped_[path] = {sg, std::move(moved)};  // for an undo: group(restore) brings it back as it is
  if (!sg->enabled) applyOuterEnabled(parent);  // its nodes are no longer inside a disabled subgraph
  bump();
  return Status::ok();
}

Status Graph::rename(const std::string& path, const std::string& new_name) {
  auto lock = lockEdits();
  const std::string what = "cannot rename '" + path + "'";
  if (!find(path) && !subgraph(path)) return Status::error(what + ": no node named '" + path + "'");
  if (new_name.find('/') != std::string::npos)
    return Status::error(what + " to '" + new_name + "': give a name, not a path (group or ungroup to move a node)");
  const std::string to = join(parentOf(path), new_name);
  if (to == path) return Status::ok();
  if (auto why = checkNewPath(to); !why.empty()) return Status::error(what + ": " + why);
  moveLocked(path, to);
  bump();
  return Status::ok();
}

void Graph::moveLocked(const std::string& from, const std::string& to) {
  auto renamed = [&](const std::string& p) {
    return p == from ? to : p.compare(0, from.size() + 1, from + "/") == 0 ? to + p.substr(from.size()) : p;
  };
  std::vector<std::string> names = nodesUnder(from);
  if (find(from)) names.push_back(from);
  for (const auto& name : names) {
    NodePtr n = find(name);
    detail::EditScope scope;  // node code and neighbours' messages read names on their groups
    scope.involveWithNeighbours(n.get());
    nodes_.erase(name);
    n->name = renamed(name);
    nodes_[n->name] = n;
  }
  std::vector<std::shared_ptr<Subgraph>> moved;
  for (auto it = subgraphs_.begin(); it != subgraphs_.end();) {
    if (renamed(it->first) == it->first) {
      ++it;
      continue;
    }
    moved.push_back(it->second);
    it = subgraphs_.erase(it);
  }
  for (auto& s : moved) {
    s->path = renamed(s->path);
    subgraphs_[s->path] = s;
  }
  for (auto& c : dormant_) {
    c.from_node = renamed(c.from_node);
    c.to_node = renamed(c.to_node);
  }
  for (auto& [path, s] : subgraphs_)  // exports naming what moved, e.g. "stage/blur/image"
    for (auto& e : s->exports)
      for (auto& i : e.inner) {
        auto [node, port] = splitEnd(i);
        const std::string full = renamed(join(path, node));
        if (full.compare(0, path.size() + 1, path + "/") == 0) i = full.substr(path.size() + 1) + "/" + port;
      }
}

// ------------------------------------------------------------------ describing

std::shared_ptr<const Manifest> Graph::facade(const Subgraph& sg) const {
  auto m = std::make_shared<Manifest>("subgraph" + (sg.source.empty() ? std::string() : " '" + sg.source + "'"));
  auto real = [&](const std::string& node) { auto n = find(node); return n && n->type ? n : nullptr; };
  for (const auto& e : sg.exports) {
    if (e.kind == Kind::Slot || e.kind == Kind::Trigger) {
      (e.kind == Kind::Slot ? m->slots : m->triggers).push_back({e.name, e.description, nullptr});
      continue;
    }
    if (e.kind == Kind::Parameter) {
      auto at = exportedParam(sg.path, e.name);
      auto n = at ? real(at.value().first) : nullptr;
      const ParamSpec* spec = n ? n->manifest().findParam(at.value().second) : nullptr;
      if (!spec) continue;
      ParamSpec s = *spec;
      s.name = e.name;
      if (!e.description.empty()) s.description = e.description;
      if (auto d = sg.defaults.find(e.name); d != sg.defaults.end())
        if (auto v = spec->parse(d->second)) s.default_value = v.value();
      m->params.push_back(std::move(s));
      continue;
    }
    std::pair<std::string, std::string> at;
    if (e.kind == Kind::Input) {
      auto all = receivers(sg.path, e.name);
      if (!all || all.value().empty()) continue;
      at = all.value().front();
    } else {
      auto one = sender(sg.path, e.name);
      if (!one) continue;
      at = one.value();
    }
    auto n = real(at.first);
    if (!n) continue;
    const Manifest& inner = n->manifest();
    const PortSpec* port = e.kind == Kind::Input ? inner.findInput(at.second) : inner.findOutput(at.second);
    PortSpec p;
    p.name = e.name;
    if (port) {
      p.type = port->type;
      p.optional = port->optional;
      p.description = port->description;
    } else if (const ParamSpec* spec = inner.findParam(at.second)) {
      p.type = spec->portType();
      p.description = spec->description;
    } else {
      continue;
    }
    if (!e.description.empty()) p.description = e.description;
    (e.kind == Kind::Input ? m->inputs : m->outputs).push_back(std::move(p));
  }
  return m;
}

GraphDescription Graph::nest(const GraphDescription& flat) const {
  GraphDescription root;
  root.thread_groups = flat.thread_groups;
  std::map<std::string, std::shared_ptr<GraphDescription>> levels;
  auto level = [&](const std::string& path) { return path.empty() ? &root : levels.at(path).get(); };
  for (const auto& n : flat.nodes)
    if (n.subgraph) levels[n.name] = std::make_shared<GraphDescription>(*n.subgraph);
  for (const auto& n : flat.nodes) {  // in insertion order
    const std::string parent = parentOf(n.name);
    if (!parent.empty() && !levels.count(parent)) continue;
    NodeDescription copy = n;
    copy.name = parent.empty() ? n.name : n.name.substr(parent.size() + 1);
    if (n.subgraph) copy.subgraph = levels[n.name];
    level(parent)->nodes.push_back(std::move(copy));
  }
  // A connection lives in the innermost subgraph holding both ends; an end inside a
  // subgraph below that is named by the export that stands for it, where there is one.
  auto ancestors = [](const std::string& path) {
    std::vector<std::string> out;
    for (std::string p = parentOf(path); !p.empty(); p = parentOf(p)) out.push_back(p);
    return out;
  };
  auto lift = [&](std::string& node, std::string& port, const std::string& at, bool sending) {
    for (std::string inst = parentOf(node); inst != at && !inst.empty(); inst = parentOf(node)) {
      auto sg = subgraph(inst);
      const std::string rel = node.substr(inst.size() + 1) + "/" + port;
      const ExportDescription* hit = nullptr;
      for (const auto& e : sg->exports)
        if ((sending ? detail::sendingExport(e.kind) : detail::receivingExport(e.kind)) &&
            std::find(e.inner.begin(), e.inner.end(), rel) != e.inner.end())
          hit = &e;
      if (!hit) return;
      node = inst;
      port = hit->name;
    }
  };
  // Several inner links may stand for one outer link (an exported input feeding two inner ones):
  // kept once. A set per level: a linear search per link made describe() quadratic (10 s at 100,000).
  std::map<std::string, std::set<std::array<std::string, 4>>> seen;
  for (auto c : flat.connections) {
    std::string at;
    const auto a = ancestors(c.from_node), b = ancestors(c.to_node);
    for (const auto& p : a)
      if (std::find(b.begin(), b.end(), p) != b.end()) {
        at = p;
        break;
      }
    if (!at.empty() && !levels.count(at)) continue;
    lift(c.from_node, c.from_port, at, true);
    lift(c.to_node, c.to_port, at, false);
    if (!at.empty()) {
      c.from_node = c.from_node.substr(at.size() + 1);
      c.to_node = c.to_node.substr(at.size() + 1);
    }
    if (seen[at].insert({c.from_node, c.from_port, c.to_node, c.to_port}).second) level(at)->connections.push_back(c);
  }
  markEdited(root, subgraphs_, "");
  return root;
}

}  // namespace apex
