// Presets: named snapshots of parameter values (of some nodes or of the whole graph),
// compared with the graph as it is and restored as one edit. The text is YAML:
//   apex_preset: 1
//   parameters:
//     threshold: {threshold: 120, type: binary}
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <stdexcept>

#include "apex_rviz_plugin/graph_model.hpp"

namespace apex_rviz_plugin {
namespace {

/** node -> [(param, value text)] in the preset's order; throws what is wrong. */
std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>> readPreset(const std::string& text) {
  const YAML::Node root = YAML::Load(text);
  if (!root.IsMap() || !root["apex_preset"] || !root["parameters"] || !root["parameters"].IsMap())
    throw std::runtime_error("not an APEX preset (it needs 'apex_preset: 1' and 'parameters')");
  std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>> out;
  for (const auto& node : root["parameters"]) {
    if (!node.second.IsMap())
      throw std::runtime_error("the parameters of '" + node.first.as<std::string>() + "' are not a mapping");
    std::vector<std::pair<std::string, std::string>> values;
    for (const auto& p : node.second) {
      YAML::Emitter value;
      value << YAML::Flow << p.second;
      values.emplace_back(p.first.as<std::string>(), value.c_str());
    }
    out.emplace_back(node.first.as<std::string>(), std::move(values));
  }
  return out;
}

}  // namespace

std::string GraphModel::preset(const std::vector<std::string>& nodes) const {
  YAML::Emitter out;
  out << YAML::BeginMap << YAML::Key << "apex_preset" << YAML::Value << 1 << YAML::Key << "parameters" << YAML::Value
      << YAML::BeginMap;
  for (const auto& n : graph_.nodes) {
    if (n.parameters.empty() || (!nodes.empty() && std::find(nodes.begin(), nodes.end(), n.name) == nodes.end())) continue;
    out << YAML::Key << n.name << YAML::Value << YAML::Flow << YAML::BeginMap;
    for (const auto& p : n.parameters) out << YAML::Key << p.name << YAML::Value << YAML::Load(p.value);
    out << YAML::EndMap;
  }
  out << YAML::EndMap << YAML::EndMap;
  return out.c_str();
}

std::vector<PresetChange> GraphModel::compare(const std::string& text, std::string* error) const {
  std::vector<PresetChange> out;
  try {
    for (const auto& [node_name, values] : readPreset(text))
      for (const auto& [param_name, then] : values) {
        const apex::ParamInfo* p = parameter(node_name, param_name);
        YAML::Emitter now;  // written as the preset writes it: the same value, the same text
        if (p) now << YAML::Flow << YAML::Load(p->value);
        if (p && std::string(now.c_str()) == then) continue;
        out.push_back({node_name, param_name, p ? p->value : "", then});
      }
  } catch (const std::exception& e) {
    if (error) *error = e.what();
  }
  return out;
}

std::optional<Edit> GraphModel::restore(const std::string& text, const std::string& name, std::string* error) const {
  Edit all("Restore preset " + name, {}, {});
  for (const auto& c : compare(text, error)) {
    auto e = c.now.empty() ? std::nullopt : setParameter(c.node, c.param, c.then);
    if (!e) continue;  // not in the graph now: compare() lists it
    all.apply.insert(all.apply.end(), e->apply.begin(), e->apply.end());
    all.revert.insert(all.revert.begin(), e->revert.begin(), e->revert.end());
  }
  if (all.apply.empty()) return std::nullopt;
  return all;
}

}  // namespace apex_rviz_plugin
