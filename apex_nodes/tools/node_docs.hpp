// docs/nodes.md from the node types' manifests: what apex_node_docs writes (scripts/node_docs) and
// what test_node_docs compares with the file in the repository. The text of ports and parameters
// is the runtime's own (toTypeInfo, as ListNodeTypes serves it to the palette); only the types of
// APEX's own node libraries (ids "apex_nodes/...") are listed, sorted, with nothing of the machine
// (no paths, no dates): the same libraries give the same file.
#pragma once

#include <algorithm>
#include <cctype>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "apex/core/categories.hpp"
#include "apex/core/registry.hpp"
#include "convert.hpp"  // apex_runtime/src/ros: toTypeInfo

namespace apex_node_docs {

/** The categories of node types, in the order the palette and docs/nodes.md list them
 *  (apex/core/categories.hpp: the panel's palette reads the same list). */
inline const std::vector<std::string>& categories() { return apex::nodeCategories(); }

/** The heading of types without a category. */
inline const std::string& kOther = apex::kOtherCategory;
/** The prefix of the ids of APEX's own node types: the ones docs/nodes.md lists. */
inline const std::string kOwnPrefix = "apex_nodes/";

inline bool isOwn(const std::string& id) { return id.compare(0, kOwnPrefix.size(), kOwnPrefix) == 0; }

namespace detail {

/** Text for a table cell: one line, '|' escaped. */
inline std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += "\\|";
    else if (c == '\n' || c == '\r') out += ' ';
    else out += c;
  }
  return out;
}

/** Code in a table cell: `text`, or nothing for empty text. */
inline std::string code(const std::string& text) {
  if (text.empty()) return "";
  const bool tick = text.find('`') != std::string::npos;
  return tick ? "`` " + cell(text) + " ``" : "`" + cell(text) + "`";
}

/** GitHub's anchor of a heading: lower case, punctuation dropped, spaces as hyphens. */
inline std::string anchor(const std::string& heading) {
  std::string out;
  for (unsigned char c : heading) {
    if (std::isalnum(c) || c == '_' || c == '-') out += static_cast<char>(std::tolower(c));
    else if (c == ' ') out += '-';
  }
  return out;
}

inline std::string capitalised(std::string s) {
  if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  return s;
}

inline std::string heading(const std::string& category) { return capitalised(category); }

/** A bound as the runtime writes values (toText): whole numbers for int ranges. */
inline std::string bound(const apex::ParamSpec& s, double v) {
  return s.kind == apex::ParamKind::IntRange ? apex::toText(apex::ParamValue(static_cast<int>(v)))
                                             : apex::toText(apex::ParamValue(v));
}

/** The range, options or path mode of a parameter; empty for kinds without any. */
inline std::string limits(const apex::ParamSpec& s, const apex::ParamInfo& p) {
  switch (s.kind) {
    case apex::ParamKind::IntRange:
    case apex::ParamKind::DoubleRange:
    case apex::ParamKind::Interval:
    case apex::ParamKind::Angle: {
      std::string text = "`[" + bound(s, p.min) + ", " + bound(s, p.max) + "]`";
      if (p.step > 0 && !(s.kind == apex::ParamKind::IntRange && p.step == 1)) text += " step `" + bound(s, p.step) + "`";
      if (s.kind == apex::ParamKind::Angle) text += " (radians)";
      return text;
    }
    case apex::ParamKind::Set: {
      std::string text;
      for (const auto& o : p.options) text += (text.empty() ? "" : ", ") + code(o);
      return text;
    }
    case apex::ParamKind::Path: {
      std::string files;
      for (const auto& o : p.options) files += (files.empty() ? "" : " ") + code(o);
      return "mode: " + p.path_mode + (files.empty() ? "" : ", files " + files);
    }
    default:
      return s.file_name ? "a file name, no path" : "";
  }
}

inline bool builtinSlot(const std::string& name) { return name == apex::kEnableSlot || name == apex::kDisableSlot; }
inline bool builtinTrigger(const std::string& name) { return name == apex::kProcessedTrigger; }

/** One type: heading, description and its tables (those it has rows for). */
inline void writeType(std::string& out, const apex::NodeType& type) {
  const apex::Manifest& m = *type.manifest;
  const apex::NodeTypeInfo info = apex::ros_host::toTypeInfo(type);
  out += "### " + type.id + "\n\n";
  out += (info.description.empty() ? std::string("(no description)") : info.description) + "\n";
  if (!info.keeps.empty()) out += "\n*Keeps from frame to frame:* " + info.keeps + ".\n";

  std::vector<const apex::PortInfo*> inputs, outputs, slots, triggers;
  for (const auto& port : info.ports) {
    if (port.kind == "input") inputs.push_back(&port);
    if (port.kind == "output") outputs.push_back(&port);
    if (port.kind == "slot" && !builtinSlot(port.name)) slots.push_back(&port);
    if (port.kind == "trigger" && !builtinTrigger(port.name)) triggers.push_back(&port);
  }
  if (!inputs.empty()) {
    out += "\n**Inputs**\n\n| name | type | optional | description |\n|---|---|---|---|\n";
    for (const auto* p : inputs)
      out += "| `" + cell(p->name) + "` | " + code(p->type) + " | " + (p->optional ? "yes" : "") + " | " + cell(p->description) +
             " |\n";
  }
  if (!outputs.empty()) {
    out += "\n**Outputs**\n\n| name | type | description |\n|---|---|---|\n";
    for (const auto* p : outputs) out += "| `" + cell(p->name) + "` | " + code(p->type) + " | " + cell(p->description) + " |\n";
  }
  const std::pair<const char*, const std::vector<const apex::PortInfo*>*> events[] = {{"Slots", &slots}, {"Triggers", &triggers}};
  for (const auto& [title, list] : events) {
    if (list->empty()) continue;
    out += std::string("\n**") + title + "**\n\n| name | description |\n|---|---|\n";
    for (const auto* p : *list) out += "| `" + cell(p->name) + "` | " + cell(p->description) + " |\n";
  }
  if (!m.params.empty()) {
    bool shapes = false;
    out += "\n**Parameters**\n\n| name | kind | range / options | default | description |\n|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < m.params.size() && i < info.parameters.size(); ++i) {
      const apex::ParamSpec& s = m.params[i];
      const apex::ParamInfo& p = info.parameters[i];
      std::string description = cell(p.description);
      std::string notes;
      if (p.interactive) notes += "has ports by default";
      if (p.shapes_ports) notes += std::string(notes.empty() ? "" : "; ") + "changes the ports";
      if (p.legacy) notes += std::string(notes.empty() ? "" : "; ") + "kept so older graphs load";
      if (!notes.empty()) description += std::string(description.empty() ? "" : " ") + "*(" + notes + ")*";
      shapes = shapes || p.shapes_ports;
      out += "| `" + cell(p.name) + "` | " + cell(p.kind) + " | " + limits(s, p) + " | " + code(p.default_value) + " | " +
             description + " |\n";
    }
    if (shapes)
      out +=
          "\nThe ports listed are those of the default parameters: the parameters marked *changes the ports* add or remove "
          "some.\n";
  }
  out += "\n";
}

}  // namespace detail

/** @brief docs/nodes.md: every type of `registry` whose id starts with "apex_nodes/", by category
 *  (categories() in order, then any other, alphabetically, then "other" for types without one),
 *  each with its description, ports, events and parameters. */
inline std::string nodeDocs(const apex::NodeRegistry& registry) {
  using namespace detail;
  std::map<std::string, std::vector<std::shared_ptr<const apex::NodeType>>> byCategory;
  std::size_t count = 0;
  for (const auto& type : registry.types()) {  // sorted by id
    if (!isOwn(type->id)) continue;
    byCategory[type->manifest->category.empty() ? kOther : type->manifest->category].push_back(type);
    ++count;
  }
  std::vector<std::string> order;
  for (const auto& c : categories())
    if (byCategory.count(c)) order.push_back(c);
  for (const auto& [c, types] : byCategory)
    if (std::find(categories().begin(), categories().end(), c) == categories().end() && c != kOther) order.push_back(c);
  if (byCategory.count(kOther)) order.push_back(kOther);

  std::string out = "# Node types\n\n";
  out +=
      "This file is generated by `scripts/node_docs` from the node types' manifests (each type's `manifest()`, "
      "next to its class under `apex_nodes/`): do not edit it by hand, but change a manifest and run "
      "`scripts/node_docs` (a test fails while this file and the manifests differ). It lists the " +
      std::to_string(count) +
      " node types of APEX's own node libraries by category, as the palette groups them. Besides the slots and "
      "triggers listed, every node has the slots `" +
      std::string(apex::kEnableSlot) + "` and `" + apex::kDisableSlot + "` and the trigger `" + apex::kProcessedTrigger +
      "`. Parameter values are written as in a graph file (YAML); angles in radians.\n\n";

  out += "## Contents\n\n";
  for (const auto& c : order) {
    const auto& types = byCategory[c];
    out += "- [" + heading(c) + "](#" + anchor(heading(c)) + "):";
    for (std::size_t i = 0; i < types.size(); ++i)
      out += std::string(i ? ", " : " ") + "[" + types[i]->id.substr(kOwnPrefix.size()) + "](#" + anchor(types[i]->id) + ")";
    out += "\n";
  }
  out += "\n";

  for (const auto& c : order) {
    out += "## " + heading(c) + "\n\n";
    for (const auto& type : byCategory[c]) writeType(out, *type);
  }
  while (out.size() > 1 && out[out.size() - 1] == '\n' && out[out.size() - 2] == '\n') out.pop_back();
  return out;
}

}  // namespace apex_node_docs
