// Subgraphs as far as they need the nodes: adding one (its nodes, connections and
// exports), removing, enabling, grouping, ungrouping and renaming, and its façade
// interface. The records alone and their rules (what a port stands for, paths, nesting
// a description) are detail::Subgraphs (subgraphs.cpp). See subgraph.hpp for the model.
#include <algorithm>
#include <map>
#include <set>

#include "apex/core/limits.hpp"
#include "apex/core/node_names.hpp"
#include "edit_scope.hpp"
#include "graph_impl.hpp"
#include "names.hpp"
#include "node_state.hpp"

namespace apex {

using detail::join;
using detail::kindName;
using detail::maskedText;
using detail::NodeState;
using detail::parentOf;
using detail::splitEnd;
using detail::Subgraph;
using Kind = ExportDescription::Kind;

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

std::vector<std::string> Graph::Impl::nodesUnder(const std::string& path) const {
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

// ------------------------------------------------------------------ adding

Status Graph::Impl::checkExports(const Subgraph& sg) const {
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
      if (auto nested = subgraphs_.find(path)) {
        auto found =
            detail::sendingExport(e.kind) ? subgraphs_.sender(path, port).status() : subgraphs_.receivers(path, port).status();
        if (!found) return Status::error(says + found.message());
        continue;
      }
      auto n = find(path);
      if (!n) return Status::error(says + "there is no " + nodeLabel(rel) + " in it");
      if (n->isPlaceholder()) continue;  // a placeholder: its ports are unknown
      const Manifest& m = n->manifest();
      const bool has = [&] {
        switch (e.kind) {
          case Kind::Input:
            return m.findInput(port) || m.findParam(port);
          case Kind::Output:
            return m.findOutput(port) || m.findParam(port);
          case Kind::Parameter:
            return m.findParam(port) != nullptr;
          case Kind::Slot:
            return m.findSlot(port) != nullptr;
          case Kind::Trigger:
            return m.findTrigger(port) != nullptr;
        }
        return false;
      }();
      if (!has) return Status::error(says + nodeLabel(path, n->typeId()) + " has no " + kindName(e.kind) + " '" + port + "'");
    }
  }
  return Status::ok();
}

Result<std::string> Graph::Impl::addSubgraph(const NodeDescription& d) {
  const std::string from = d.source.empty() ? "" : " ('" + d.source + "')";
  if (!d.subgraph)
    return Status::error(subgraphLabel(d.name) + from + " was not read: subgraph files are read with the graph file");
  auto sg = std::make_shared<Subgraph>();
  {
    auto lock = lockEdits();
    if (auto why = checkNewPath(d.name); !why.empty()) return Status::error(why);
    std::set<std::string> more;  // the limit counts the groups it would add, together
    for (const auto& g : d.subgraph->thread_groups) {
      if (!validName(g)) return Status::error(subgraphLabel(d.name) + ": thread group name '" + g + "' " + kNameRule);
      if (!groups_.count(g)) more.insert(g);
    }
    if (groups_.size() + more.size() > kMaxGraphGroups)
      return Status::error(subgraphLabel(d.name) + ": its " + std::to_string(more.size()) + " new thread groups would " +
                           "pass the limit of " + std::to_string(kMaxGraphGroups) + " (the graph has " +
                           std::to_string(groups_.size()) + ")");
    sg->path = d.name;
    sg->source = d.source;
    sg->seq = next_seq_++;
    sg->thread_groups = d.subgraph->thread_groups;
    sg->exports = d.subgraph->exports;
    sg->ui = d.ui;
    for (const auto& g : sg->thread_groups) group(g);
    subgraphs_.put(sg);
    bump();
  }
  auto undo = [&](int line, const std::string& why) {
    (void)removeNode(d.name);
    return Status::error(subgraphLabel(d.name) + from + ": " + (line ? "line " + std::to_string(line) + ": " : "") + why);
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
      auto real = subgraphs_.exportedParam(d.name, e.name);
      auto n = real ? find(real.value().first) : nullptr;
      const int i = n && n->type() ? n->findParam(real.value().second) : -1;
      if (i < 0) continue;
      sg->defaults[e.name] = toText(n->requestedParam(i));
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

void Graph::Impl::removeSubgraphLocked(const std::string& path) {
  for (const auto& name : nodesUnder(path)) {
    auto n = find(name);
    retire(n.get());
    order_.erase(n->seq());
    nodes_.erase(name);
  }
  subgraphs_.erase(path);
  const std::string prefix = path + "/";
  dormant_.erase(std::remove_if(dormant_.begin(), dormant_.end(),
                                [&](const auto& c) {
                                  return c.from_node.compare(0, prefix.size(), prefix) == 0 ||
                                         c.to_node.compare(0, prefix.size(), prefix) == 0;
                                }),
                 dormant_.end());
}

void Graph::Impl::applyOuterEnabled(const std::string& path) {
  for (const auto& name : nodesUnder(path)) {
    const bool outer = subgraphs_.enabledAround(name);
    NodeState& n = *find(name);
    n.setOuterEnabled(outer);
    if (n.type()) n.post([](NodeState& x) { x.applyEnabled(); });
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

Status Graph::group(const std::vector<std::string>& members, const std::string& name, bool restore) {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  auto fail = [&](const std::string& why) { return Status::error("cannot group into '" + name + "': " + why); };
  if (members.empty()) return fail("no nodes given");
  const std::string parent = parentOf(members.front());
  std::set<std::string> seen;
  for (const auto& m : members) {
    if (!impl.find(m) && !impl.subgraphs_.find(m)) return fail("no node named '" + m + "'");
    if (parentOf(m) != parent)
      return fail("'" + m + "' and '" + members.front() + "' are not beside each other (group nodes of one level)");
    if (!seen.insert(m).second) return fail("'" + m + "' is named twice");
  }
  const std::string path = join(parent, name);
  if (auto why = impl.checkNewPath(path); !why.empty()) return fail(why);
  auto inside = [&](const std::string& node) {
    for (const auto& m : members)
      if (node == m || node.compare(0, m.size() + 1, m + "/") == 0) return true;
    return false;
  };
  auto rel = [&](const std::string& node, const std::string& port) {
    return node.substr(parent.empty() ? 0 : parent.size() + 1) + "/" + port;
  };
  std::shared_ptr<Subgraph> before = restore ? impl.subgraphs_.takeUngrouped(path, members) : nullptr;
  // Each crossing connection through an export: one per outside sender (it may feed several
  // inner receivers), one per inner sender (it may feed several outside).
  auto sg = std::make_shared<Subgraph>();
  std::set<std::string> sending, receiving;
  std::map<std::string, std::size_t> by_sender;  // "node/port" → index in exports
  auto cross = [&](const std::string& from, const std::string& from_port, const std::string& to, const std::string& to_port,
                   bool event) {
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
  for (auto& [seq, n] : impl.order_) {
    const Manifest& m = n->manifest();
    auto target = [](const detail::Edge& e) {
      return e.to_param ? e.to->manifest().params[e.to_index].name : e.to->manifest().inputs[e.to_index].name;
    };
    if (n->isPlaceholder()) continue;
    for (std::size_t i = 0; i < m.outputs.size(); ++i)
      for (auto& e : n->outputEdges(int(i))) cross(n->name(), m.outputs[i].name, e->to->name(), target(*e), false);
    for (std::size_t i = 0; i < m.params.size(); ++i)
      for (auto& e : n->paramOutEdges(int(i))) cross(n->name(), m.params[i].name, e->to->name(), target(*e), false);
    for (std::size_t i = 0; i < m.triggers.size(); ++i)
      for (auto& e : n->triggerEdges(int(i)))
        cross(n->name(), m.triggers[i].name, e->to->name(), e->to->manifest().slots[e->slot].name, true);
  }
  sg->path = path;
  sg->seq = ~0ull;  // before the first of its nodes, where it stands in the order
  for (const auto& m : members) {
    if (auto n = impl.find(m)) sg->seq = std::min(sg->seq, n->seq());
    if (auto s = impl.subgraphs_.find(m)) sg->seq = std::min(sg->seq, s->seq);
    for (const auto& under : impl.nodesUnder(m)) sg->seq = std::min(sg->seq, impl.find(under)->seq());
  }
  if (auto first = impl.find(members.front())) {
    sg->ui = first->ui();
  } else {
    sg->ui = impl.subgraphs_.find(members.front())->ui;
  }
  impl.subgraphs_.put(sg);
  for (const auto& m : members) impl.moveLocked(m, join(path, m.substr(parent.empty() ? 0 : parent.size() + 1)));
  if (before && impl.checkExports(*before)) {  // as it was; its exports cover what crosses, as they did
    before->seq = sg->seq;
    impl.subgraphs_.put(before);
    if (!before->enabled) impl.applyOuterEnabled(path);
  }
  impl.bump();
  return Status::ok();
}

Status Graph::ungroup(const std::string& path) {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  auto sg = impl.subgraphs_.find(path);
  if (!sg)
    return Status::error("cannot ungroup '" + path +
                         "': " + (impl.find(path) ? "it is not a subgraph" : "no node named '" + path + "'"));
  const std::string parent = parentOf(path);
  std::vector<std::string> children;
  for (const auto& [name, n] : impl.nodes_)
    if (parentOf(name) == path) children.push_back(name);
  for (const auto& name : impl.subgraphs_.inside(path)) children.push_back(name);
  for (const auto& c : children) {
    const std::string to = join(parent, c.substr(path.size() + 1));
    if (to != path && (impl.find(to) || impl.subgraphs_.find(to)))
      return Status::error("cannot ungroup '" + path + "': its " + nodeLabel(c.substr(path.size() + 1)) +
                           " would take the name of the " + nodeLabel(to) + " beside it (rename one first)");
  }
  impl.subgraphs_.dissolve(path);
  for (const auto& c : children) impl.moveLocked(c, join(parent, c.substr(path.size() + 1)));
  std::set<std::string> moved;
  for (const auto& c : children) moved.insert(join(parent, c.substr(path.size() + 1)));
  impl.subgraphs_.recordUngrouped(sg, std::move(moved));  // for an undo: impl.group(restore) brings it back as it is
  if (!sg->enabled) impl.applyOuterEnabled(parent);  // its nodes are no longer inside a disabled subgraph
  impl.bump();
  return Status::ok();
}

Status Graph::rename(const std::string& path, const std::string& new_name) {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  const std::string what = "cannot rename '" + path + "'";
  if (!impl.find(path) && !impl.subgraphs_.find(path)) return Status::error(what + ": no node named '" + path + "'");
  if (new_name.find('/') != std::string::npos)
    return Status::error(what + " to '" + new_name + "': give a name, not a path (group or ungroup to move a node)");
  const std::string to = join(parentOf(path), new_name);
  if (to == path) return Status::ok();
  if (auto why = impl.checkNewPath(to); !why.empty()) return Status::error(what + ": " + why);
  impl.moveLocked(path, to);
  impl.bump();
  return Status::ok();
}

void Graph::Impl::moveLocked(const std::string& from, const std::string& to) {
  auto renamed = [&](const std::string& p) { return detail::movedPath(p, from, to); };
  std::vector<std::string> names = nodesUnder(from);
  if (find(from)) names.push_back(from);
  for (const auto& name : names) {
    Impl::NodePtr n = find(name);
    detail::EditScope scope;  // node code and neighbours' messages read names on their groups
    scope.involveWithNeighbours(n.get());
    nodes_.erase(name);
    n->rename(renamed(name));
    nodes_[n->name()] = n;
  }
  subgraphs_.move(from, to);
  for (auto& c : dormant_) {
    c.from_node = renamed(c.from_node);
    c.to_node = renamed(c.to_node);
  }
}

// ------------------------------------------------------------------ describing

std::shared_ptr<const Manifest> Graph::Impl::facade(const Subgraph& sg) const {
  auto m = std::make_shared<Manifest>("subgraph" + (sg.source.empty() ? std::string() : " '" + sg.source + "'"));
  auto real = [&](const std::string& node) {
    auto n = find(node);
    return n && n->type() ? n : nullptr;
  };
  for (const auto& e : sg.exports) {
    if (e.kind == Kind::Slot || e.kind == Kind::Trigger) {
      (e.kind == Kind::Slot ? m->slots : m->triggers).push_back({e.name, e.description, nullptr});
      continue;
    }
    if (e.kind == Kind::Parameter) {
      auto at = subgraphs_.exportedParam(sg.path, e.name);
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
      auto all = subgraphs_.receivers(sg.path, e.name);
      if (!all || all.value().empty()) continue;
      at = all.value().front();
    } else {
      auto one = subgraphs_.sender(sg.path, e.name);
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

}  // namespace apex
