// Graph YAML as text: parsed into a GraphDescription and formatted from one (with param_text.cpp
// for single values). The only code that reads and writes the format; graph_file.cpp does files.
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

#include "apex/core/graph_file.hpp"
#include "apex/core/node_names.hpp"
#include "apex/core/text.hpp"
#include "yaml_load.hpp"
#include "yaml_text.hpp"

namespace apex {
namespace {

int lineOf(const YAML::Node& n) { return n.Mark().line < 0 ? 1 : n.Mark().line + 1; }  // an empty file has no mark

std::string flow(const YAML::Node& n) {
  YAML::Emitter e;
  e << YAML::Flow << n;
  return e.c_str();
}

struct ParseError {
  std::string message;
};

[[noreturn]] void fail(const YAML::Node& at, const std::string& what) {
  throw ParseError{"line " + std::to_string(lineOf(at)) + ": " + what};
}

void onlyKeys(const YAML::Node& map, const std::set<std::string>& known, const std::string& what) {
  std::set<std::string> seen;
  for (const auto& kv : map) {
    const auto key = kv.first.as<std::string>();
    if (!seen.insert(key).second) fail(kv.first, what + ": the key '" + key + "' appears twice");
    if (known.count(key)) continue;
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    fail(kv.first, what + ": unknown key '" + key + "' (known keys: " + list + ")");
  }
}

std::string scalar(const YAML::Node& map, const char* key, const std::string& what, bool required = true) {
  const YAML::Node v = map[key];
  if (!v) {
    if (required) fail(map, what + ": '" + key + "' is missing");
    return {};
  }
  if (!v.IsScalar()) fail(v, what + ": '" + key + "' must be a single value");
  return v.as<std::string>();
}

GraphDescription parseBody(const YAML::Node& map, int version, int depth);

/** A node, or (format 2) a subgraph instance: `subgraph:` a file reference or an inline graph. */
NodeDescription parseNode(const YAML::Node& n, int version, int depth) {
  if (!n.IsMap()) fail(n, "a node must be a mapping with at least 'name' and 'type'");
  NodeDescription d;
  d.line = lineOf(n);
  d.name = scalar(n, "name", "node");
  const std::string what = nodeLabel(d.name);
  const YAML::Node sub = n["subgraph"];
  if (sub && version < 2) fail(sub, what + ": subgraphs need 'apex_graph: 2'");
  if (sub) {
    onlyKeys(n, {"name", "subgraph", "enabled", "parameters", "interactive", "ui"}, what + " (a subgraph)");
    d.type = kSubgraphType;
    if (sub.IsScalar()) {
      d.source = sub.as<std::string>();
      if (d.source.empty()) fail(sub, what + ": 'subgraph' names no file");
    } else if (sub.IsMap()) {
      if (depth >= kMaxSubgraphDepth)
        fail(sub, what + ": subgraphs nested deeper than " + std::to_string(kMaxSubgraphDepth) + " levels");
      d.subgraph = std::make_shared<GraphDescription>(parseBody(sub, version, depth + 1));
    } else {
      fail(sub, what + ": 'subgraph' must be a graph file's name or a graph (a mapping with 'nodes')");
    }
  } else {
    onlyKeys(n, {"name", "type", "thread_group", "enabled", "parameters", "interactive", "ui"}, what);
    d.type = scalar(n, "type", what);
    d.thread_group = scalar(n, "thread_group", what, false);
  }
  if (d.thread_group.empty()) d.thread_group = kDefaultGroup;
  if (const auto e = n["enabled"]) {
    if (!e.IsScalar() || !YAML::convert<bool>::decode(e, d.enabled)) fail(e, what + ": 'enabled' must be true or false");
  }
  if (const auto p = n["parameters"]) {
    if (!p.IsMap()) fail(p, what + ": 'parameters' must be a mapping of name: value");
    std::set<std::string> seen;
    for (const auto& kv : p) {
      const auto name = kv.first.as<std::string>();
      if (!seen.insert(name).second) fail(kv.first, what + ": the parameter '" + name + "' appears twice");
      d.parameters.emplace_back(name, flow(kv.second));
    }
  }
  if (const auto i = n["interactive"]) {
    if (!i.IsSequence()) fail(i, what + ": 'interactive' must be a list of parameter names");
    for (const auto& name : i) d.interactive.push_back(name.as<std::string>());
  }
  if (const auto ui = n["ui"]) d.ui = flow(ui);
  return d;
}

/** "node/port": split at the last '/', so the node may be a path into subgraphs ("a/b/port"). */
std::pair<std::string, std::string> splitEndpoint(const YAML::Node& at, const std::string& text, const std::string& what) {
  const auto slash = text.rfind('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == text.size())
    fail(at, what + ": '" + text + "' must look like node/port");
  return {text.substr(0, slash), text.substr(slash + 1)};
}

std::pair<std::string, std::string> endpoint(const YAML::Node& c, const char* key) {
  return splitEndpoint(c[key], scalar(c, key, "connection"), "connection: '" + std::string(key) + "'");
}

using ExportKind = ExportDescription::Kind;
const std::vector<std::pair<std::string, ExportKind>>& exportKinds() {
  static const std::vector<std::pair<std::string, ExportKind>> kinds{{"input", ExportKind::Input},
                                                                     {"output", ExportKind::Output},
                                                                     {"parameter", ExportKind::Parameter},
                                                                     {"slot", ExportKind::Slot},
                                                                     {"trigger", ExportKind::Trigger}};
  return kinds;
}

/** `{input: image, to: blur/image}`, `{output: regions, from: find/regions}`, ... */
ExportDescription parseExport(const YAML::Node& e) {
  if (!e.IsMap()) fail(e, "an export must be a mapping such as {input: image, to: blur/image}");
  ExportDescription x;
  x.line = lineOf(e);
  int kinds = 0;
  for (const auto& [key, kind] : exportKinds())
    if (e[key]) {
      ++kinds;
      x.kind = kind;
      x.name = scalar(e, key.c_str(), "export");
    }
  if (kinds != 1) fail(e, "an export names one of input, output, parameter, slot, trigger (and what it stands for)");
  const bool inward = x.kind != ExportKind::Output && x.kind != ExportKind::Trigger;
  const char* side = inward ? "to" : "from";
  const std::string what = "export '" + x.name + "'";
  std::set<std::string> keys{"description", side};
  for (const auto& kv : exportKinds()) keys.insert(kv.first);
  onlyKeys(e, keys, what);
  const YAML::Node inner = e[side];
  if (!inner) fail(e, what + ": '" + side + "' is missing (the inner node/port it stands for)");
  const bool many = x.kind == ExportKind::Input || x.kind == ExportKind::Slot;
  if (inner.IsSequence() && many) {
    for (const auto& item : inner) x.inner.push_back(item.as<std::string>());
    if (x.inner.empty()) fail(inner, what + ": '" + side + "' is an empty list");
  } else if (inner.IsScalar()) {
    x.inner.push_back(inner.as<std::string>());
  } else {
    fail(inner, what + ": '" + side + "' must be one node/port" + (many ? " or a list of them" : ""));
  }
  for (const auto& i : x.inner) splitEndpoint(inner, i, what);
  x.description = scalar(e, "description", what, false);
  return x;
}

std::string tooMany(std::size_t n, const char* what, std::size_t limit) {
  return std::to_string(n) + " " + what + ", over the limit of " + std::to_string(limit);
}

/** Everything the format does not use is refused before it is read: tags (!!binary, !custom),
 *  nesting deeper than kMaxYamlDepth, long strings, and more than kMaxYamlNodes values counted
 *  through aliases (an alias bomb expands exponentially). */
void checkTree(const YAML::Node& root) {
  std::vector<std::pair<YAML::Node, int>> stack{{root, 0}};
  std::size_t visited = 0;
  while (!stack.empty()) {
    auto [n, depth] = stack.back();
    stack.pop_back();
    if (++visited > kMaxYamlNodes) fail(root, "more than " + std::to_string(kMaxYamlNodes) + " values (aliases included)");
    if (depth > kMaxYamlDepth) fail(n, "nested deeper than " + std::to_string(kMaxYamlDepth) + " levels");
    const std::string& tag = n.Tag();
    if (!tag.empty() && tag != "?" && tag != "!") fail(n, "the tag '" + tag + "' is not part of the graph format");
    if (n.IsScalar() && n.Scalar().size() > kMaxYamlString)
      fail(n, "a value of " + std::to_string(n.Scalar().size()) + " characters, over the limit of " +
                  std::to_string(kMaxYamlString));
    if (n.IsSequence()) {
      for (const auto& item : n) stack.push_back({item, depth + 1});
    } else if (n.IsMap()) {
      for (const auto& kv : n) {
        stack.push_back({kv.first, depth + 1});
        stack.push_back({kv.second, depth + 1});
      }
    }
  }
}

/** Thread groups, nodes, connections and exports: a whole graph, or an inline subgraph. */
GraphDescription parseBody(const YAML::Node& root, int version, int depth) {
  GraphDescription d;
  if (const auto g = root["thread_groups"]) {
    if (!g.IsSequence()) fail(g, "'thread_groups' must be a list of names");
    if (g.size() > kMaxGraphGroups) fail(g, tooMany(g.size(), "thread groups", kMaxGraphGroups));
    for (const auto& name : g) d.thread_groups.push_back(name.as<std::string>());
  }
  if (const auto nodes = root["nodes"]) {
    if (!nodes.IsSequence()) fail(nodes, "'nodes' must be a list");
    if (nodes.size() > kMaxGraphNodes) fail(nodes, tooMany(nodes.size(), "nodes", kMaxGraphNodes));
    for (const auto& n : nodes) d.nodes.push_back(parseNode(n, version, depth));
  }
  if (const auto conns = root["connections"]) {
    if (!conns.IsSequence()) fail(conns, "'connections' must be a list");
    if (conns.size() > kMaxGraphConnections) fail(conns, tooMany(conns.size(), "connections", kMaxGraphConnections));
    for (const auto& c : conns) {
      if (!c.IsMap()) fail(c, "a connection must be a mapping {from: node/port, to: node/port}");
      onlyKeys(c, {"from", "to"}, "connection");
      auto [fn, fp] = endpoint(c, "from");
      auto [tn, tp] = endpoint(c, "to");
      d.connections.push_back({fn, fp, tn, tp, lineOf(c)});
    }
  }
  if (const auto exports = root["exports"]) {
    if (version < 2) fail(exports, "'exports' needs 'apex_graph: 2'");
    if (!exports.IsSequence()) fail(exports, "'exports' must be a list such as [{input: image, to: blur/image}]");
    for (const auto& e : exports) d.exports.push_back(parseExport(e));
  }
  return d;
}

GraphDescription parseRoot(const YAML::Node& root) {
  checkTree(root);
  if (!root.IsMap() || !root["apex_graph"])
    fail(root,
         "not an APEX graph: the file must be a mapping with the key 'apex_graph: " + std::to_string(kGraphFormatVersion) + "'");
  onlyKeys(root, {"apex_graph", "thread_groups", "nodes", "connections", "exports"}, "graph");
  int version = 0;
  if (!YAML::convert<int>::decode(root["apex_graph"], version)) fail(root["apex_graph"], "'apex_graph' must be a version number");
  if (version < 1 || version > kGraphFormatVersion)
    fail(root["apex_graph"], "graph format " + std::to_string(version) + " is not supported (this APEX reads formats 1 to " +
                                 std::to_string(kGraphFormatVersion) + ")");
  return parseBody(root, version, 0);
}

// The style goes on the node: YAML::Flow on the emitter would leak into what follows.
void emitValue(YAML::Emitter& out, const std::string& text) {
  YAML::Node value = YAML::Load(text);
  value.SetStyle(YAML::EmitterStyle::Flow);
  out << value;
}

/** The line where a second YAML document starts, if the text has one. (Not YAML::LoadAll: in
 *  yaml-cpp 0.7 it never returns on some malformed text, e.g. a lone ",": found by fuzzing.) */
int secondDocumentLine(const std::string& text) {
  struct Starts : YAML::EventHandler {
    YAML::Mark start;
    void OnDocumentStart(const YAML::Mark& mark) override { start = mark; }
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
    void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
    void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
    void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
    void OnSequenceEnd() override {}
    void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
    void OnMapEnd() override {}
  } starts;
  std::istringstream in(text);
  YAML::Parser parser(in);
  if (!parser.HandleNextDocument(starts) || !parser.HandleNextDocument(starts)) return 0;
  return starts.start.line < 0 ? 1 : starts.start.line + 1;
}

}  // namespace

namespace {
/** False for .nan, .inf, -.Inf (YAML's) and a number past a double's range (1e309). */
bool finiteIfNumber(const std::string& text) {
  double v = 0;
  if (YAML::convert<double>::decode(YAML::Node(text), v)) return std::isfinite(v);
  if (text.find_first_of("0123456789") == std::string::npos) return true;
  char* end = nullptr;
  v = std::strtod(text.c_str(), &end);
  return end != text.c_str() + text.size() || std::isfinite(v);
}
}  // namespace

namespace detail {
Status checkYamlText(const std::string& text) {
  if (text.size() > kMaxYamlString)
    return Status::error("has " + std::to_string(text.size()) + " characters, over the limit of " +
                         std::to_string(kMaxYamlString));
  if (auto st = checkText(text); !st) return Status::error("is not text: " + st.message());
  try {
    const YAML::Node root = loadYaml(text);
    checkTree(root);  // what a graph file may hold, so that the graph saved with it loads
    std::vector<YAML::Node> stack{root};
    while (!stack.empty()) {
      const YAML::Node n = stack.back();
      stack.pop_back();
      if (n.IsScalar() && !finiteIfNumber(n.Scalar()))  // quoted too: a file writes it back plain
        return Status::error("holds '" + n.Scalar() + "', a number that is not finite");
      for (const auto& item : n) stack.push_back(n.IsMap() ? item.second : item);
    }
    return Status::ok();
  } catch (const YAML::Exception& e) {
    return Status::error("is not valid YAML: " + e.msg);
  } catch (const ParseError& e) {
    return Status::error("is refused: " + e.message);
  }
}
bool isGraphText(const std::string& text) {
  try {
    const YAML::Node root = loadYaml(text);
    return root.IsMap() && root["apex_graph"];
  } catch (const YAML::Exception&) {
    return false;
  }
}
}  // namespace detail

Result<std::vector<std::pair<std::string, std::string>>> parseParameterMap(const std::string& text) {
  std::vector<std::pair<std::string, std::string>> out;
  try {
    const YAML::Node map = detail::loadYaml(text);
    if (!map || map.IsNull()) return out;
    if (!map.IsMap()) return Status::error("'" + text + "' is not a YAML mapping of parameter: value");
    for (const auto& kv : map) out.emplace_back(kv.first.as<std::string>(), flow(kv.second));
    return out;
  } catch (const YAML::Exception& e) {
    return Status::error("'" + text + "' is not valid YAML: " + e.msg);
  }
}

Result<GraphDescription> parseGraphText(const std::string& text) {
  try {
    const YAML::Node root = detail::loadYaml(text);  // the first document
    if (const int line = secondDocumentLine(text))
      throw ParseError{"line " + std::to_string(line) + ": a graph file holds one YAML document, and this is a second one"};
    return parseRoot(root);
  } catch (const ParseError& e) {
    return Status::error(e.message);
  } catch (const YAML::Exception& e) {  // syntax errors carry their position
    return Status::error("line " + std::to_string(e.mark.line + 1) + ", column " + std::to_string(e.mark.column + 1) + ": " +
                         e.msg);
  }
}

namespace {

void emitBody(YAML::Emitter& out, const GraphDescription& d);

void emitNode(YAML::Emitter& out, const NodeDescription& n) {
  out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << n.name;
  if (!n.source.empty()) {
    out << YAML::Key << "subgraph" << YAML::Value << n.source;
  } else if (n.subgraph) {
    out << YAML::Key << "subgraph" << YAML::Value << YAML::BeginMap;
    emitBody(out, *n.subgraph);
    out << YAML::EndMap;
  } else {
    out << YAML::Key << "type" << YAML::Value << n.type;
    if (n.thread_group != kDefaultGroup) out << YAML::Key << "thread_group" << YAML::Value << n.thread_group;
  }
  if (!n.enabled) out << YAML::Key << "enabled" << YAML::Value << false;
  if (!n.parameters.empty()) {
    out << YAML::Key << "parameters" << YAML::Value << YAML::BeginMap;
    for (const auto& [name, text] : n.parameters) {
      out << YAML::Key << name << YAML::Value;
      emitValue(out, text);
    }
    out << YAML::EndMap;
  }
  if (!n.interactive.empty()) out << YAML::Key << "interactive" << YAML::Value << YAML::Flow << n.interactive;
  if (!n.ui.empty()) {
    out << YAML::Key << "ui" << YAML::Value;
    emitValue(out, n.ui);
  }
  out << YAML::EndMap;
}

void emitExport(YAML::Emitter& out, const ExportDescription& e) {
  const bool inward = e.kind != ExportDescription::Kind::Output && e.kind != ExportDescription::Kind::Trigger;
  std::string key;
  for (const auto& [k, kind] : exportKinds())
    if (kind == e.kind) key = k;
  out << YAML::Flow << YAML::BeginMap << YAML::Key << key << YAML::Value << e.name << YAML::Key << (inward ? "to" : "from")
      << YAML::Value;
  if (e.inner.size() == 1) {
    out << e.inner.front();
  } else {
    out << YAML::Flow << e.inner;
  }
  if (!e.description.empty()) out << YAML::Key << "description" << YAML::Value << e.description;
  out << YAML::EndMap;
}

void emitBody(YAML::Emitter& out, const GraphDescription& d) {
  if (!d.thread_groups.empty()) out << YAML::Key << "thread_groups" << YAML::Value << YAML::Flow << d.thread_groups;
  if (!d.exports.empty()) {
    out << YAML::Key << "exports" << YAML::Value << YAML::BeginSeq;
    for (const auto& e : d.exports) emitExport(out, e);
    out << YAML::EndSeq;
  }
  out << YAML::Key << "nodes" << YAML::Value;
  if (d.nodes.empty()) out << YAML::Flow;  // "nodes: []"
  out << YAML::BeginSeq;
  for (const auto& n : d.nodes) emitNode(out, n);
  out << YAML::EndSeq << YAML::Key << "connections" << YAML::Value;
  if (d.connections.empty()) out << YAML::Flow;  // "connections: []"
  out << YAML::BeginSeq;
  for (const auto& c : d.connections) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "from" << YAML::Value << c.from_node + "/" + c.from_port << YAML::Key
        << "to" << YAML::Value << c.to_node + "/" + c.to_port << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

}  // namespace

std::string formatGraphText(const GraphDescription& d) {
  YAML::Emitter out;
  out << YAML::BeginMap << YAML::Key << "apex_graph" << YAML::Value << kGraphFormatVersion;
  emitBody(out, d);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace apex
