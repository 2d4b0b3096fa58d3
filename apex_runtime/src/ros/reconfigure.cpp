// How APEX parameters look to dynamic_reconfigure (rqt_reconfigure, dynparam, Client):
//   bool -> bool; int, int range -> int; double, double range, angle (radians) -> double, with
//   their bounds (none: the type's limits); string, path -> str; a set -> str with an enum of its
//   options; interval, pair, colour, list, text list -> str holding the YAML text that
//   `set_parameter` takes ("[0.2, 0.8]", "[255, 0, 0]").
#include "reconfigure.hpp"

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <dynamic_reconfigure/Reconfigure.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "apex/core/node_names.hpp"

namespace apex {
namespace ros_host {
namespace {

using dynamic_reconfigure::Config;
using dynamic_reconfigure::ConfigDescription;

enum class Field { Bool, Int, Double, Str };

Field fieldOf(const ParamSpec& p) {
  switch (p.kind) {
    case ParamKind::Bool:
      return Field::Bool;
    case ParamKind::Int:
    case ParamKind::IntRange:
      return Field::Int;
    case ParamKind::Double:
    case ParamKind::DoubleRange:
    case ParamKind::Angle:
      return Field::Double;
    default:
      return Field::Str;
  }
}

const char* typeName(Field f) {
  switch (f) {
    case Field::Bool:
      return "bool";
    case Field::Int:
      return "int";
    case Field::Double:
      return "double";
    default:
      return "str";
  }
}

bool bounded(const ParamSpec& p) {
  return p.kind == ParamKind::IntRange || p.kind == ParamKind::DoubleRange || p.kind == ParamKind::Angle;
}

/** Appends `value` of parameter `p` to a Config under its dynamic_reconfigure type. */
void put(Config& c, const ParamSpec& p, const ParamValue& value) {
  switch (fieldOf(p)) {
    case Field::Bool: {
      dynamic_reconfigure::BoolParameter b;
      b.name = p.name, b.value = std::holds_alternative<bool>(value) && std::get<bool>(value);
      c.bools.push_back(b);
      return;
    }
    case Field::Int: {
      dynamic_reconfigure::IntParameter i;
      i.name = p.name, i.value = std::holds_alternative<int>(value) ? std::get<int>(value) : 0;
      c.ints.push_back(i);
      return;
    }
    case Field::Double: {
      dynamic_reconfigure::DoubleParameter d;
      d.name = p.name, d.value = std::holds_alternative<double>(value) ? std::get<double>(value) : 0.0;
      c.doubles.push_back(d);
      return;
    }
    case Field::Str: {
      dynamic_reconfigure::StrParameter s;
      s.name = p.name;
      s.value = std::holds_alternative<std::string>(value) ? std::get<std::string>(value) : toText(value);
      c.strs.push_back(s);
      return;
    }
  }
}

/** A bound of `p` as a value of its field's type: its range where it has one, else the type's limit. */
ParamValue bound(const ParamSpec& p, bool upper) {
  const double limit = upper ? p.max : p.min;
  switch (fieldOf(p)) {
    case Field::Bool:
      return upper;
    case Field::Int:
      return bounded(p) ? static_cast<int>(limit) : (upper ? std::numeric_limits<int>::max() : std::numeric_limits<int>::min());
    case Field::Double:
      return bounded(p) ? limit : (upper ? 1.0 : -1.0) * std::numeric_limits<double>::infinity();
    default:
      return std::string();
  }
}

/** Text as a Python string literal (rqt_reconfigure evaluates edit_method). */
std::string pythonString(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\\' || c == '\'') out += '\\';
    out += c;
  }
  return out + "'";
}

/** A set's options as dynamic_reconfigure's enum edit method. */
std::string enumOf(const ParamSpec& p) {
  std::string items;
  for (const auto& o : p.options) {
    items += std::string(items.empty() ? "" : ", ") + "{'name': " + pythonString(o) +
             ", 'type': 'str', 'value': " + pythonString(o) + ", 'description': " + pythonString(o) +
             ", 'srcline': 0, 'srcfile': '', 'cconsttype': 'const char * const', 'ctype': 'std::string'}";
  }
  return "{'enum': [" + items + "], 'enum_description': " + pythonString(p.description) + "}";
}

void addDefaultGroup(Config& c) {
  dynamic_reconfigure::GroupState g;
  g.name = "Default", g.state = true, g.id = 0, g.parent = 0;
  c.groups.push_back(g);
}

ConfigDescription describeParams(const Manifest& m) {
  ConfigDescription d;
  dynamic_reconfigure::Group group;
  group.name = "Default", group.id = 0, group.parent = 0;
  for (const auto& p : m.params) {
    dynamic_reconfigure::ParamDescription pd;
    pd.name = p.name;
    pd.type = typeName(fieldOf(p));
    pd.level = 0;
    pd.description = p.description;
    if (p.kind == ParamKind::Set) pd.edit_method = enumOf(p);
    group.parameters.push_back(pd);
    put(d.min, p, bound(p, false));
    put(d.max, p, bound(p, true));
    put(d.dflt, p, p.default_value);
  }
  d.groups.push_back(group);
  addDefaultGroup(d.min), addDefaultGroup(d.max), addDefaultGroup(d.dflt);
  return d;
}

/** The node's current values (none of a node that is gone). */
Config valuesOf(const Graph& graph, const std::string& node, const Manifest& m) {
  Config c;
  for (const auto& p : m.params)
    if (auto v = graph.parameterValue(node, p.name)) put(c, p, v.value());
  addDefaultGroup(c);
  return c;
}

/** A requested value as the YAML text set_parameter takes; strings of plain kinds are quoted,
 *  those of YAML kinds (interval, colour, lists) are the text itself. */
std::string textOf(const ParamSpec* p, const std::string& s) {
  const bool plain = !p || p->kind == ParamKind::String || p->kind == ParamKind::Path || p->kind == ParamKind::Set;
  return plain ? toText(ParamValue(s)) : s;
}

std::string numberText(double d) { return toText(ParamValue(d)); }

/** A summary of a description or values, to publish only what changed. */
template <class M>
std::string keyOf(const M& msg) {
  std::vector<std::uint8_t> buffer(ros::serialization::serializationLength(msg));
  ros::serialization::OStream out(buffer.data(), static_cast<std::uint32_t>(buffer.size()));
  ros::serialization::serialize(out, msg);
  return std::string(buffer.begin(), buffer.end());
}

}  // namespace

struct Reconfigure::Server {
  ros::ServiceServer service;
  ros::Publisher descriptions, updates;
  std::string described, valued;  // what was last published
};

Reconfigure::Reconfigure(ros::NodeHandle pnh, Graph& graph, Setter set, int limit)
    : pnh_(pnh), graph_(graph), set_(std::move(set)), limit_(limit) {}

Reconfigure::~Reconfigure() = default;

void Reconfigure::update(const GraphState& state) {
  std::map<std::string, std::unique_ptr<Server>> kept;
  int made = 0, served = 0;
  std::size_t unserved = 0;
  pending_ = false;
  for (const auto& node : state.nodes) {
    if (node.state == "placeholder" || node.parameters.empty()) continue;  // nothing to reconfigure
    const auto iface = graph_.nodeInterface(node.name);
    if (!iface || iface->params.empty()) continue;  // removed or changed meanwhile
    if (++served > limit_) {  // the first nodes with parameters, in the graph's order
      ++unserved;
      continue;
    }
    auto it = servers_.find(node.name);
    std::unique_ptr<Server> server;
    if (it != servers_.end()) {
      server = std::move(it->second);
    } else if (made == kMadePerUpdate) {
      pending_ = true;
      continue;
    } else {
      ++made;
      try {
        ros::NodeHandle nh(pnh_, node.name);
        server = std::make_unique<Server>();
        server->descriptions = nh.advertise<ConfigDescription>("parameter_descriptions", 1, true);
        server->updates = nh.advertise<Config>("parameter_updates", 1, true);
        const std::string name = node.name;
        server->service =
            nh.advertiseService<dynamic_reconfigure::Reconfigure::Request, dynamic_reconfigure::Reconfigure::Response>(
                "set_parameters",
                [this, name](dynamic_reconfigure::Reconfigure::Request& req, dynamic_reconfigure::Reconfigure::Response& res) {
                  return setParameters(name, req.config, res.config);
                });
      } catch (const ros::InvalidNameException& e) {
        ROS_WARN_STREAM_NAMED("apex", nodeLabel(node.name) << ": no dynamic_reconfigure server: " << e.what());
        continue;
      }
    }
    const ConfigDescription description = describeParams(*iface);
    if (std::string key = keyOf(description); key != server->described) {
      server->descriptions.publish(description);
      server->described = std::move(key);
      server->valued.clear();  // a client that reads the new description wants the values again
    }
    const Config values = valuesOf(graph_, node.name, *iface);
    if (std::string key = keyOf(values); key != server->valued) {
      server->updates.publish(values);
      server->valued = std::move(key);
    }
    kept[node.name] = std::move(server);
  }
  servers_ = std::move(kept);  // the rest shut down with their handles
  if (unserved > 0 && unserved != unserved_)
    ROS_WARN_STREAM_NAMED("apex", "dynamic_reconfigure serves the first " << limit_ << " nodes with parameters, not " << unserved
                                                                          << " more (~dynamic_reconfigure_limit); "
                                                                          << "set_parameter sets any node's");
  unserved_ = unserved;
}

bool Reconfigure::setParameters(const std::string& node, const Config& request, Config& applied) {
  const auto iface = graph_.nodeInterface(node);
  if (!iface) throw std::runtime_error("there is no " + nodeLabel(node));
  std::vector<std::pair<std::string, std::string>> changes;  // parameter, YAML text
  for (const auto& b : request.bools) changes.emplace_back(b.name, b.value ? "true" : "false");
  for (const auto& i : request.ints) changes.emplace_back(i.name, std::to_string(i.value));
  for (const auto& d : request.doubles) changes.emplace_back(d.name, numberText(d.value));
  for (const auto& s : request.strs) changes.emplace_back(s.name, textOf(iface->findParam(s.name), s.value));
  // All or nothing: a refused value puts back what this call set before it.
  std::vector<std::pair<std::string, ParamValue>> before;
  for (const auto& [param, text] : changes) {
    auto old = graph_.parameterValue(node, param);
    auto done = set_(node, param, text);
    if (!done) {
      for (auto it = before.rbegin(); it != before.rend(); ++it) (void)graph_.setParameter(node, it->first, toText(it->second));
      ROS_WARN_STREAM_NAMED("apex", "dynamic_reconfigure of '" << node << "' refused: " << done.message());
      throw std::invalid_argument(done.message());  // roscpp answers with this text as the error
    }
    if (old) before.emplace_back(param, old.value());
  }
  applied = valuesOf(graph_, node, *iface);
  return true;
}

}  // namespace ros_host
}  // namespace apex
