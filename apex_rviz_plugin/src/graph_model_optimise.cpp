// GraphModel, tuning: a parameter given to an Optimizer (a new one or one of the graph's) as one
// edit, and the Optimizer's best values applied as one edit.
#include "apex_rviz_plugin/graph_model.hpp"

#include <yaml-cpp/yaml.h>

#include <set>

#include "calls.hpp"

namespace apex_rviz_plugin {
namespace {

using namespace calls;

/** A text list parameter's value (YAML) as strings; empty if it cannot be read. */
std::vector<std::string> textList(const std::string& yaml) {
  try {
    const YAML::Node n = YAML::Load(yaml);
    return n.IsSequence() ? n.as<std::vector<std::string>>() : std::vector<std::string>{};
  } catch (const YAML::Exception&) {
    return {};
  }
}

std::string yamlList(const std::vector<std::string>& items) {
  YAML::Emitter out;
  out << YAML::Flow << items;
  return out.c_str();
}

/** A value as a parameter's text: a scalar as it is, an interval as "[low, high]". */
std::string flowText(const YAML::Node& value) {
  if (value.IsScalar()) return value.Scalar();
  YAML::Emitter out;
  out << YAML::Flow << value;
  return out.c_str();
}

}  // namespace

std::optional<std::string> tunedAs(const apex::ParamInfo& p) {
  if (p.shapes_ports) return std::nullopt;
  if (p.type == "double") return std::string();
  if (p.type == "int") return std::string(" int");
  if (p.kind == "interval") return std::string(" interval");
  if (p.kind == "set") return std::string(" choice");
  if (p.kind == "bool") return std::string(" bool");
  return std::nullopt;
}

std::vector<std::string> GraphModel::optimizers() const {
  std::vector<std::string> out;
  for (const auto& n : graph_.nodes)
    if (n.type == kOptimizerType) out.push_back(n.name);
  return out;
}

std::optional<Edit> GraphModel::optimise(const std::string& node_name, const std::string& param, const std::string& optimizer,
                                         double x, double y, const apex::NodeTypeInfo* optimizer_type) const {
  const apex::ParamInfo* p = parameter(node_name, param);
  const auto how = p ? tunedAs(*p) : std::nullopt;
  if (!how) return std::nullopt;
  for (const auto& c : graph_.connections)  // a parameter input has one source
    if (c.to_node == node_name && c.to_port == param) return std::nullopt;
  const bool make = optimizer.empty();
  if (make && !optimizer_type) return std::nullopt;  // a new Optimizer's own names unknown: not guessed
  const std::string opt = make ? freshName(kOptimizerType) : optimizer;
  std::vector<std::string> dims;
  if (!make) {
    const apex::ParamInfo* d = parameter(opt, "dimensions");
    if (!d) return std::nullopt;
    dims = textList(d->value);
  }
  // A dimension is an output of the Optimizer: named after the parameter, unless taken by one of
  // its own ports, events or parameters (as its type lists them, and as the node in the graph
  // has them) or by another dimension.
  std::set<std::string> own;
  auto add = [&own](const auto& ports, const auto& params) {
    for (const auto& q : ports) own.insert(q.name);
    for (const auto& q : params) own.insert(q.name);
  };
  if (optimizer_type) add(optimizer_type->ports, optimizer_type->parameters);
  if (const apex::NodeInfo* o = make ? nullptr : node(opt)) add(o->ports, o->parameters);
  auto taken = [&](const std::string& name) {
    if (own.count(name)) return true;
    for (const auto& d : dims)
      if (d.substr(0, d.find(' ')) == name) return true;
    return false;
  };
  std::string dim = param;
  for (int k = 2; taken(dim); ++k) dim = node_name + "_" + param + (k > 2 ? "_" + std::to_string(k - 1) : "");
  const std::string old_dims = yamlList(dims);
  dims.push_back(dim + *how);

  Edit e{"Optimise " + node_name + "/" + param + " with " + opt, {}, {}};
  if (make) e.apply = addNode(kOptimizerType, opt, x, y).apply;
  if (!p->interactive) e.apply.push_back(interactive(node_name, param, true));
  e.apply.push_back(setParam(opt, "dimensions", yamlList(dims)));
  const apex::Connection link = [&] {
    apex::Connection c;
    c.from_node = opt, c.from_port = dim, c.to_node = node_name, c.to_port = param;
    return c;
  }();
  e.apply.push_back(calls::connect("connect", link));
  e.revert.push_back(calls::connect("disconnect", link));
  if (make) {
    apex::RemoveNode::Request remove;
    remove.name = opt;
    e.revert.push_back({"remove_node", remove});
  } else {
    e.revert.push_back(setParam(opt, "dimensions", old_dims));
  }
  if (!p->interactive) e.revert.push_back(interactive(node_name, param, false));
  return e;
}

namespace {

/** A text parameter's value read as YAML (it holds YAML: best_values, front); null if it cannot be. */
YAML::Node yamlIn(const apex::ParamInfo* p) {
  if (!p) return {};
  try {
    return YAML::Load(YAML::Load(p->value).as<std::string>());
  } catch (const YAML::Exception&) {
    return {};
  }
}

/** Not while it runs: its state reads 'running: ...' or 'starting: ...'. */
bool isRunning(const apex::ParamInfo* state) {
  return state && (state->value.find("running") <= 1 || state->value.find("starting") <= 1);
}

}  // namespace

std::optional<Edit> GraphModel::applyValues(const std::string& opt, const YAML::Node& values, const std::string& label) const {
  if (!values.IsMap() || isRunning(parameter(opt, "state"))) return std::nullopt;
  Edit e{label, {}, {}};
  for (const auto& c : graph_.connections) {
    if (c.from_node != opt || !values[c.from_port]) continue;
    const apex::ParamInfo* target = parameter(c.to_node, c.to_port);
    if (!target) continue;
    e.apply.push_back(setParam(c.to_node, c.to_port, flowText(values[c.from_port])));
    e.revert.push_back(setParam(c.to_node, c.to_port, target->value));
  }
  if (e.apply.empty()) return std::nullopt;
  return e;
}

std::optional<Edit> GraphModel::applyBest(const std::string& opt) const {
  return applyValues(opt, yamlIn(parameter(opt, "best_values")), "Apply the best values of " + opt);
}

std::vector<FrontPoint> GraphModel::front(const std::string& opt) const { return frontIn(parameter(opt, "front")); }

std::vector<FrontPoint> frontIn(const apex::ParamInfo* param) {
  std::vector<FrontPoint> out;
  const YAML::Node front = yamlIn(param);
  if (!front.IsSequence()) return out;
  try {
    for (const auto& p : front)
      out.push_back(
          {p["evaluation"].as<int>(), p["fitness"].as<double>(), p["ms_per_frame"].as<double>(), flowText(p["values"])});
  } catch (const YAML::Exception&) {
    return {};
  }
  return out;
}

std::optional<Edit> GraphModel::applyFrontPoint(const std::string& opt, int evaluation) const {
  const YAML::Node front = yamlIn(parameter(opt, "front"));
  if (!front.IsSequence()) return std::nullopt;
  for (const auto& p : front)
    if (p["evaluation"] && p["evaluation"].as<std::string>() == std::to_string(evaluation))
      return applyValues(opt, p["values"], "Apply evaluation " + std::to_string(evaluation) + " of " + opt + "'s front");
  return std::nullopt;
}

}  // namespace apex_rviz_plugin
