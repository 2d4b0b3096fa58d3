// Subgraph bookkeeping (detail::Subgraphs in subgraph.hpp): the records by path, what a
// subgraph's ports stand for, how records follow a rename or an ungroup, and nesting the
// flat graph back into subgraphs to describe or save it. Nothing here sees a node.
#include <algorithm>
#include <array>
#include <map>
#include <set>

#include "apex/core/graph_file.hpp"
#include "apex/core/node_names.hpp"
#include "names.hpp"
#include "subgraph.hpp"

namespace apex {
namespace detail {

using Kind = ExportDescription::Kind;

namespace {

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
  for (auto& [name, text] : n->parameters)
    if (name == param) text = "~";
  n->interactive.erase(std::remove(n->interactive.begin(), n->interactive.end(), param), n->interactive.end());
  if (!n->subgraph) return;
  auto inner = std::make_shared<GraphDescription>(*n->subgraph);
  n->subgraph = inner;
  for (const auto& e : inner->exports)
    if (e.kind == Kind::Parameter && e.name == param) mask(*inner, e.inner.front());
}

/** Inner-first: a file-backed subgraph whose inner graph no longer reads as its file made it
 *  is described inline, so that saving keeps the edit. */
void markEdited(GraphDescription& g, const Subgraphs::Records& subgraphs, const std::string& prefix) {
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

const char* kindName(Kind k) {
  switch (k) {
    case Kind::Input:
      return "input";
    case Kind::Output:
      return "output";
    case Kind::Parameter:
      return "parameter";
    case Kind::Slot:
      return "slot";
    case Kind::Trigger:
      return "trigger";
  }
  return "";
}

std::string maskedText(const GraphDescription& inner, const std::vector<ExportDescription>& exports) {
  GraphDescription g = inner;
  for (const auto& e : exports)
    if (e.kind == Kind::Parameter) mask(g, e.inner.front());
  return formatGraphText(g);
}

// ------------------------------------------------------------------ records and paths

std::shared_ptr<Subgraph> Subgraphs::find(const std::string& path) const {
  auto it = records_.find(path);
  return it == records_.end() ? nullptr : it->second;
}

std::vector<std::string> Subgraphs::inside(const std::string& path) const {
  std::vector<std::string> out;
  for (const auto& [name, s] : records_)
    if (parentOf(name) == path) out.push_back(name);
  return out;
}

std::string Subgraphs::checkNewPath(const std::string& path, bool node_there) const {
  std::size_t start = 0;
  while (true) {
    const auto slash = path.find('/', start);
    if (!validName(path.substr(start, slash - start)))
      return "node name '" + path + "' " + kNameRule +
             (path.find('/') == std::string::npos ? "" : " (in each part of a path a/b)");
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  if (node_there || records_.count(path)) return "a node named '" + path + "' already exists";
  const std::string parent = parentOf(path);
  if (!parent.empty() && !records_.count(parent))
    return "node name '" + path + "': there is no " + subgraphLabel(parent) + " to put it in";
  return "";
}

bool Subgraphs::enabledAround(const std::string& path) const {
  for (std::string p = parentOf(path); !p.empty(); p = parentOf(p))
    if (auto sg = find(p); sg && !sg->enabled) return false;
  return true;
}

void Subgraphs::put(std::shared_ptr<Subgraph> sg) {
  const std::string path = sg->path;
  records_[path] = std::move(sg);
}

void Subgraphs::erase(const std::string& path) {
  const std::string prefix = path + "/";
  for (auto it = records_.begin(); it != records_.end();)
    it = it->first == path || it->first.compare(0, prefix.size(), prefix) == 0 ? records_.erase(it) : std::next(it);
}

void Subgraphs::clear() {
  records_.clear();
  ungrouped_.clear();
}

// ------------------------------------------------------------------ what a port stands for

Result<std::pair<std::string, std::string>> Subgraphs::sender(const std::string& node, const std::string& port) const {
  auto sg = find(node);
  if (!sg) return std::make_pair(node, port);
  for (const auto& e : sg->exports) {
    if (e.name != port || !sendingExport(e.kind)) continue;
    auto [n, p] = splitEnd(e.inner.front());
    return sender(join(node, n), p);
  }
  return Status::error(subgraphLabel(node) + " exports no output, trigger or parameter '" + port +
                       "' (it exports: " + listExports(*sg, sendingExport) + ")");
}

Result<std::vector<std::pair<std::string, std::string>>> Subgraphs::receivers(const std::string& node,
                                                                              const std::string& port) const {
  std::vector<std::pair<std::string, std::string>> out;
  auto sg = find(node);
  if (!sg) {
    out.emplace_back(node, port);
    return out;
  }
  for (const auto& e : sg->exports) {
    if (e.name != port || !receivingExport(e.kind)) continue;
    for (const auto& inner : e.inner) {
      auto [n, p] = splitEnd(inner);
      auto more = receivers(join(node, n), p);
      if (!more) return more;
      out.insert(out.end(), more.value().begin(), more.value().end());
    }
    return out;
  }
  return Status::error(subgraphLabel(node) + " exports no input, slot or parameter '" + port +
                       "' (it exports: " + listExports(*sg, receivingExport) + ")");
}

Result<std::pair<std::string, std::string>> Subgraphs::exportedParam(const std::string& node, const std::string& param) const {
  auto sg = find(node);
  if (!sg) return std::make_pair(node, param);
  for (const auto& e : sg->exports) {
    if (e.name != param || e.kind != Kind::Parameter) continue;
    auto [n, p] = splitEnd(e.inner.front());
    return exportedParam(join(node, n), p);
  }
  std::string list;
  for (const auto& e : sg->exports)
    if (e.kind == Kind::Parameter) list += (list.empty() ? "" : ", ") + e.name;
  return Status::error(subgraphLabel(node) + " exports no parameter '" + param +
                       "' (parameters: " + (list.empty() ? "none" : list) + ")");
}

// ------------------------------------------------------------------ edits

void Subgraphs::move(const std::string& from, const std::string& to) {
  std::vector<std::shared_ptr<Subgraph>> moved;
  for (auto it = records_.begin(); it != records_.end();) {
    if (movedPath(it->first, from, to) == it->first) {
      ++it;
      continue;
    }
    moved.push_back(it->second);
    it = records_.erase(it);
  }
  for (auto& s : moved) {
    s->path = movedPath(s->path, from, to);
    records_[s->path] = s;
  }
  for (auto& [path, s] : records_)  // exports naming what moved, e.g. "stage/blur/image"
    for (auto& e : s->exports)
      for (auto& i : e.inner) {
        auto [node, port] = splitEnd(i);
        const std::string full = movedPath(join(path, node), from, to);
        if (full.compare(0, path.size() + 1, path + "/") == 0) i = full.substr(path.size() + 1) + "/" + port;
      }
}

void Subgraphs::dropExportsOf(const std::string& node) {
  for (std::string parent = parentOf(node), rel = node.substr(node.rfind('/') + 1); !parent.empty();
       rel = parent.substr(parent.rfind('/') + 1) + "/" + rel, parent = parentOf(parent)) {
    auto sg = find(parent);
    if (!sg) continue;
    for (auto& e : sg->exports)
      e.inner.erase(
          std::remove_if(e.inner.begin(), e.inner.end(), [&](const std::string& i) { return splitEnd(i).first == rel; }),
          e.inner.end());
    sg->exports.erase(std::remove_if(sg->exports.begin(), sg->exports.end(), [](const auto& e) { return e.inner.empty(); }),
                      sg->exports.end());
  }
}

void Subgraphs::dissolve(const std::string& path) {
  auto sg = find(path);
  const std::string parent = parentOf(path);
  if (auto around = find(parent)) {  // its exports that stood for this one's: for what those stood for
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
          if (x.name == port && (sendingExport(e.kind) ? sendingExport(x.kind) : receivingExport(x.kind)))
            inner.insert(inner.end(), x.inner.begin(), x.inner.end());
      }
      e.inner = std::move(inner);
    }
  }
  records_.erase(path);
}

void Subgraphs::recordUngrouped(std::shared_ptr<Subgraph> sg, std::set<std::string> members) {
  const std::string path = sg->path;
  ungrouped_[path] = {std::move(sg), std::move(members)};
}

std::shared_ptr<Subgraph> Subgraphs::takeUngrouped(const std::string& path, const std::vector<std::string>& members) {
  auto it = ungrouped_.find(path);
  if (it == ungrouped_.end()) return nullptr;
  auto [sg, had] = std::move(it->second);
  ungrouped_.erase(it);
  return std::set<std::string>(members.begin(), members.end()) == had ? sg : nullptr;
}

// ------------------------------------------------------------------ nesting

GraphDescription Subgraphs::nest(const GraphDescription& flat) const {
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
      auto sg = find(inst);
      const std::string rel = node.substr(inst.size() + 1) + "/" + port;
      const ExportDescription* hit = nullptr;
      for (const auto& e : sg->exports)
        if ((sending ? sendingExport(e.kind) : receivingExport(e.kind)) &&
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
  markEdited(root, records_, "");
  return root;
}

}  // namespace detail
}  // namespace apex
