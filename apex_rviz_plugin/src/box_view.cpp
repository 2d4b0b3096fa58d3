#include "apex_rviz_plugin/box_view.hpp"
#include "apex/core/description.hpp"

#include <cmath>
#include <cstdio>

#include <yaml-cpp/yaml.h>

#include <algorithm>

namespace apex_rviz_plugin {
namespace {

YAML::Node mapOf(const std::string& ui_text) {
  if (ui_text.empty()) return YAML::Node(YAML::NodeType::Map);
  try {
    YAML::Node u = YAML::Load(ui_text);
    if (u.IsMap()) return u;
  } catch (const YAML::Exception&) {  // metadata another front end wrote differently: replaced
  }
  return YAML::Node(YAML::NodeType::Map);
}

bool atDefault(const apex::ParamInfo& p) { return p.value == p.default_value; }

/** The parameters a box can list: all but legacy ones at their defaults. */
std::size_t listed(const apex::NodeInfo& node) {
  std::size_t n = 0;
  for (const auto& p : node.parameters) n += !(p.legacy && atDefault(p));
  return n;
}

}  // namespace

BoxView BoxView::of(const std::string& ui_text) {
  BoxView v;
  const YAML::Node u = mapOf(ui_text);
  try {
    if (u["expanded"] && u["expanded"].IsScalar()) v.expanded = u["expanded"].as<bool>();
    if (u["pinned"] && u["pinned"].IsSequence())
      for (const auto& p : u["pinned"]) v.pinned.push_back(p.as<std::string>());
  } catch (const YAML::Exception&) {  // a value of another shape: the defaults
  }
  return v;
}

bool BoxView::isPinned(const std::string& param) const { return std::find(pinned.begin(), pinned.end(), param) != pinned.end(); }

bool BoxView::collapsible(const apex::NodeInfo& node) { return listed(node) > kFewParams; }

bool BoxView::isExpanded(const apex::NodeInfo& node) const { return expanded ? *expanded : !collapsible(node); }

std::vector<std::string> BoxView::shown(const apex::NodeInfo& node) const {
  const bool all = isExpanded(node);
  std::vector<std::string> out;
  for (const auto& p : node.parameters) {
    if (p.legacy && atDefault(p)) continue;
    const auto in = [&p](const std::vector<std::string>& names) {
      return std::find(names.begin(), names.end(), p.name) != names.end();
    };
    // a file or folder to choose: without it the node does nothing (a player, a writer, a model)
    const bool needed = p.kind == "path" || in(pinned) || in(always);
    if (all || needed || ((!atDefault(p) || p.interactive) && !in(elsewhere))) out.push_back(p.name);
  }
  return out;
}

std::size_t BoxView::hidden(const apex::NodeInfo& node) const { return listed(node) - shown(node).size(); }

std::string withUiKey(const std::string& ui_text, const std::string& key, const std::string& yaml_value) {
  YAML::Node u = mapOf(ui_text);
  u[key] = YAML::Load(yaml_value);
  YAML::Emitter out;
  out << YAML::Flow << u;
  return out.c_str();
}

std::string withPosition(const std::string& ui_text, double x, double y) {
  return withUiKey(withUiKey(ui_text, "x", std::to_string(static_cast<int>(x))), "y", std::to_string(static_cast<int>(y)));
}

std::string scalarText(double v) {
  char text[64];
  const double a = std::fabs(v);
  if (std::isfinite(v) && a >= 1e5 && a < 1e15) {
    std::snprintf(text, sizeof text, "%.3f", v);
    std::string t = text;
    while (t.back() == '0') t.pop_back();
    if (t.back() == '.') t.pop_back();
    return t;
  }
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

std::string kindLine(const std::string& type, const std::string& thread_group) {
  return thread_group.empty() || thread_group == apex::kDefaultGroup ? type : type + "  · group " + thread_group;
}

std::string playerPlace(long frame, long last, bool last_known, double time_s, bool playing, bool loops) {
  std::string out = "frame " + std::to_string(frame);  // as the `frame` parameter counts: from 0
  if (last_known) out += " / " + std::to_string(last + 1);
  char time[48];
  std::snprintf(time, sizeof time, " · %.2f s", time_s);
  out += time;
  if (last_known && frame >= last && !loops) return "ended · " + out;  // the pass is over: its last frame held
  return playing ? out : "held · " + out;
}

}  // namespace apex_rviz_plugin
