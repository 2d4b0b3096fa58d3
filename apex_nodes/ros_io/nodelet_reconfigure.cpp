// NodeletHost's mirror of a nodelet's dynamic_reconfigure parameters (nodelet_reconfigure.hpp).
#include "nodelet_reconfigure.hpp"

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>

#include "apex/core/param.hpp"

namespace apex_nodes {
namespace nodelet_host {
namespace {

using dynamic_reconfigure::Config;
using dynamic_reconfigure::ConfigDescription;

std::string seconds(double s) {
  std::ostringstream out;
  out << s << " s";
  return out.str();
}

/** `name`'s value in `c` as YAML, typed as dynamic_reconfigure's `type` says; nullopt if absent. */
template <class Emit>
bool emitValue(const Config& c, const std::string& name, Emit emit) {
  for (const auto& p : c.bools)
    if (p.name == name) return emit(static_cast<bool>(p.value)), true;
  for (const auto& p : c.ints)
    if (p.name == name) return emit(p.value), true;
  for (const auto& p : c.doubles)
    if (p.name == name) return emit(p.value), true;
  for (const auto& p : c.strs)
    if (p.name == name) return emit(p.value), true;
  return false;
}

std::optional<double> number(const Config& c, const std::string& name) {
  for (const auto& p : c.ints)  // dynamic_reconfigure's "no bound" for ints is the type's limit
    if (p.name == name && std::abs(static_cast<double>(p.value)) < std::numeric_limits<int>::max()) return p.value;
  for (const auto& p : c.doubles)
    if (p.name == name && std::isfinite(p.value)) return p.value;
  return std::nullopt;
}

/** An enum's options from dynamic_reconfigure's edit_method (a Python dict's text, which YAML
 *  reads): name and value text each; none if it is not an enum. */
void emitOptions(YAML::Emitter& e, const std::string& edit_method) {
  if (edit_method.empty()) return;
  YAML::Node root;
  try {
    root = YAML::Load(edit_method);
  } catch (const YAML::Exception&) {
    return;  // not an enum we can read: the parameter stays a number or text
  }
  if (!root.IsMap() || !root["enum"] || !root["enum"].IsSequence()) return;
  e << YAML::Key << "options" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const auto& item : root["enum"])
    if (item["name"] && item["value"])
      e << YAML::Flow << YAML::BeginSeq << item["name"].as<std::string>() << item["value"].as<std::string>() << YAML::EndSeq;
  e << YAML::EndSeq;
}

/** `name`'s value in `c` as YAML text ("" if absent). */
std::string valueText(const Config& c, const std::string& name) {
  YAML::Emitter e;
  e.SetDoublePrecision(17);
  return emitValue(c, name, [&](const auto& v) { e << v; }) ? std::string(e.c_str()) : std::string();
}

/** The parameters of NodeletHost and NodeletSource themselves: an offered one of the same name
 *  gets a prefix. A fixed list, so the name does not depend on which others are there. */
bool hostParam(const std::string& name) {
  for (const char* p : {"nodelet", "inputs", "outputs", "timeout", "config", "remap", "reconfigure"})
    if (name == p) return true;
  return false;
}

apex::Result<Offered> parseEntry(const std::string& text) {
  auto bad = [&](const std::string& why) { return apex::Status::error("reconfigure: entry '" + text + "': " + why); };
  YAML::Node n;
  try {
    n = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    return bad(std::string("not YAML: ") + e.what());
  }
  if (!n.IsMap() || !n["name"] || !n["type"] || !n["value"]) return bad("needs name, type and value");
  try {
    Offered o;
    o.name = n["name"].as<std::string>();
    o.type = n["type"].as<std::string>();
    o.param = hostParam(o.name) ? "nodelet_" + o.name : o.name;
    o.value = YAML::Dump(n["value"]);
    if (n["min"]) o.min = n["min"].as<double>();
    if (n["max"]) o.max = n["max"].as<double>();
    if (n["description"]) o.description = n["description"].as<std::string>();
    if (n["options"])
      for (const auto& opt : n["options"]) o.options.emplace_back(opt[0].as<std::string>(), opt[1].as<std::string>());
    if (o.type != "bool" && o.type != "int" && o.type != "double" && o.type != "str")
      return bad("type '" + o.type + "' is none of bool, int, double, str");
    return o;
  } catch (const YAML::Exception& e) {
    return bad(e.what());
  }
}

/** The enum option whose value is `value` (YAML text), or "": numbers compared as numbers (the
 *  description's 0.1 and an emitted 0.10000000000000001 are one value). */
std::string optionOf(const Offered& o, const std::string& value) {
  const YAML::Node want = YAML::Load(value);
  double a = 0, b = 0;
  const bool number = YAML::convert<double>::decode(want, a);
  for (const auto& [name, v] : o.options) {
    const YAML::Node have = YAML::Load(v);
    if (number ? YAML::convert<double>::decode(have, b) && a == b : have.as<std::string>() == want.as<std::string>()) return name;
  }
  return "";
}

apex::Result<apex::ParamSpec> specOf(const Offered& o) {
  const YAML::Node v = YAML::Load(o.value);
  apex::ParamSpec s;
  if (!o.options.empty()) {
    std::vector<std::string> names;
    for (const auto& opt : o.options) names.push_back(opt.first);
    const std::string current = v.IsNull() ? std::string() : optionOf(o, o.value);
    s = apex::param::options(o.param, names, current.empty() ? names.front() : current);
  } else if (o.type == "bool") {
    s = apex::param::boolean(o.param, v.as<bool>());
  } else if (o.type == "int") {
    s = o.min && o.max ? apex::param::range(o.param, int(*o.min), int(*o.max), 1, v.as<int>())
                       : apex::param::integer(o.param, v.as<int>());
  } else if (o.type == "double") {
    s = o.min && o.max ? apex::param::range(o.param, *o.min, *o.max, (*o.max - *o.min) / 1000, v.as<double>())
                       : apex::param::real(o.param, v.as<double>());
  } else {
    s = apex::param::text(o.param, v.IsNull() ? std::string() : v.as<std::string>());
  }
  s.describe((o.description.empty() ? o.name : o.description) + " (the nodelet's '" + o.name + "', through dynamic_reconfigure)");
  if (auto st = s.validate(s.default_value); !st) return apex::Status::error("reconfigure: '" + o.name + "': " + st.message());
  return s;
}

}  // namespace

// Its value is the nodelet's default, not the one it has now: the entries stay the same across
// loads (no edit of `reconfigure` after each), and the values the nodelet has come apart (Offers).
std::string entryOf(const dynamic_reconfigure::ParamDescription& p, const ConfigDescription& d) {
  YAML::Emitter e;
  e.SetDoublePrecision(17);
  e << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << p.name << YAML::Key << "type" << YAML::Value
    << p.type << YAML::Key << "value" << YAML::Value;
  if (!emitValue(d.dflt, p.name, [&](const auto& v) { e << v; })) e << YAML::Null;
  if (auto min = number(d.min, p.name)) e << YAML::Key << "min" << YAML::Value << *min;
  if (auto max = number(d.max, p.name)) e << YAML::Key << "max" << YAML::Value << *max;
  e << YAML::Key << "description" << YAML::Value << p.description;
  emitOptions(e, p.edit_method);
  e << YAML::EndMap;
  return e.c_str();
}

Offers offeredBy(HostedNodelet& nodelet, double timeout) {
  const std::string descriptions = nodelet.name() + "/parameter_descriptions", updates = nodelet.name() + "/parameter_updates";
  ros::V_string advertised;
  ros::this_node::getAdvertisedTopics(advertised);
  if (std::find(advertised.begin(), advertised.end(), descriptions) == advertised.end()) return {};
  struct Got {
    std::mutex m;
    std::optional<ConfigDescription> description;
    std::optional<Config> values;
  };
  auto got = std::make_shared<Got>();
  ros::NodeHandle nh = nodelet.handle();
  auto a = nh.subscribe<ConfigDescription>(descriptions, 1, [got](const dynamic_reconfigure::ConfigDescriptionConstPtr& m) {
    std::lock_guard<std::mutex> lock(got->m);
    got->description = *m;
  });
  auto b = nh.subscribe<Config>(updates, 1, [got](const dynamic_reconfigure::ConfigConstPtr& m) {
    std::lock_guard<std::mutex> lock(got->m);
    got->values = *m;
  });
  const bool came = nodelet.spinUntil(
      [&] {
        std::lock_guard<std::mutex> lock(got->m);
        return got->description && got->values;
      },
      timeout);
  a.shutdown();
  b.shutdown();
  std::lock_guard<std::mutex> lock(got->m);
  if (!came)
    throw std::runtime_error(nodelet.describe() + " advertises " + descriptions + " but sent no description and values within " +
                             seconds(timeout));
  Offers out;
  for (const auto& group : got->description->groups)
    for (const auto& p : group.parameters) {
      out.entries.push_back(entryOf(p, *got->description));
      out.values[p.name] = valueText(*got->values, p.name);
    }
  std::sort(out.entries.begin(), out.entries.end());
  return out;
}

apex::Result<std::vector<Offered>> parseOffered(const std::vector<std::string>& entries) {
  std::vector<Offered> out;
  for (const auto& e : entries) {
    auto o = parseEntry(e);
    if (!o) return o.status();
    out.push_back(*o);
  }
  return out;
}

apex::Status addOffered(const std::vector<std::string>& entries, apex::Manifest& m) {
  auto offered = parseOffered(entries);
  if (!offered) return offered.status();
  for (const auto& o : *offered) {
    auto spec = specOf(o);
    if (!spec) return spec.status();
    m.param(*spec);
  }
  return apex::Status::ok();
}

std::optional<apex::ParamValue> valueOf(const Offered& o, const std::string& text) {
  if (text.empty()) return std::nullopt;
  Offered now = o;
  now.value = text;
  if (!o.options.empty() && optionOf(o, text).empty()) return std::nullopt;  // not one of its options
  auto spec = specOf(now);  // its default is that value
  if (!spec) return std::nullopt;
  return spec->default_value;
}

XmlRpc::XmlRpcValue toNodelet(const Offered& o, const apex::ParamValue& value) {
  if (!o.options.empty()) {
    const auto& name = std::get<std::string>(value);
    for (const auto& [option, v] : o.options)
      if (option == name) {
        if (o.type == "int") return XmlRpc::XmlRpcValue(YAML::Load(v).as<int>());
        if (o.type == "double") return XmlRpc::XmlRpcValue(YAML::Load(v).as<double>());
        return XmlRpc::XmlRpcValue(YAML::Load(v).as<std::string>());
      }
    throw std::invalid_argument("'" + o.param + "': no option '" + name + "'");
  }
  if (o.type == "bool") return XmlRpc::XmlRpcValue(std::get<bool>(value));
  if (o.type == "int") return XmlRpc::XmlRpcValue(std::get<int>(value));
  if (o.type == "double") return XmlRpc::XmlRpcValue(std::get<double>(value));
  return XmlRpc::XmlRpcValue(std::get<std::string>(value));
}

void reconfigure(HostedNodelet& nodelet, const Offered& o, const apex::ParamValue& value, double timeout) {
  XmlRpc::XmlRpcValue v = toNodelet(o, value);
  dynamic_reconfigure::Reconfigure call;
  auto& c = call.request.config;
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      c.bools.emplace_back().name = o.name, c.bools.back().value = static_cast<bool>(v);
      break;
    case XmlRpc::XmlRpcValue::TypeInt:
      c.ints.emplace_back().name = o.name, c.ints.back().value = static_cast<int>(v);
      break;
    case XmlRpc::XmlRpcValue::TypeDouble:
      c.doubles.emplace_back().name = o.name, c.doubles.back().value = static_cast<double>(v);
      break;
    default:
      c.strs.emplace_back().name = o.name, c.strs.back().value = static_cast<std::string>(v);
  }
  // The server answers on the nodelet's queue, which this thread may be the one to spin.
  auto answered = std::make_shared<bool>(false);
  const auto aside = [service = nodelet.name() + "/set_parameters", call, answered]() mutable {
    *answered = ros::service::call(service, call);
  };
  if (!nodelet.callAside(aside, timeout))
    throw std::runtime_error(nodelet.describe() + " did not answer setting '" + o.name + "' within " + seconds(timeout));
  if (!*answered)
    throw std::runtime_error(nodelet.describe() + ": setting '" + o.name + "' failed (its " + nodelet.name() +
                             "/set_parameters service did not answer)");
}

}  // namespace nodelet_host
}  // namespace apex_nodes
