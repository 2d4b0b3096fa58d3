#include "apex/core/manifest.hpp"

#include <set>

#include "names.hpp"

namespace apex {
namespace {

template <class T>
const T* find(const std::vector<T>& items, const std::string& name) {
  for (const auto& i : items)
    if (i.name == name) return &i;
  return nullptr;
}

template <class T>
std::string names(const std::vector<T>& items) {
  if (items.empty()) return "none";
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ", ") + i.name;
  return s;
}

}  // namespace

const PortSpec* Manifest::findInput(const std::string& n) const { return find(inputs, n); }
const PortSpec* Manifest::findOutput(const std::string& n) const { return find(outputs, n); }
const ParamSpec* Manifest::findParam(const std::string& n) const { return find(params, n); }
const EventSpec* Manifest::findSlot(const std::string& n) const { return find(slots, n); }
const EventSpec* Manifest::findTrigger(const std::string& n) const { return find(triggers, n); }
std::string Manifest::listInputs() const { return names(inputs); }
std::string Manifest::listOutputs() const { return names(outputs); }
std::string Manifest::listParams() const { return names(params); }
std::string Manifest::listSlots() const { return names(slots); }
std::string Manifest::listTriggers() const { return names(triggers); }

Status Manifest::check() const {
  const Manifest& m = *this;
  auto bad = [](const std::string& what) { return Status::error(what); };
  std::set<std::string> to_side, from_side;  // names a connection's target / source may use
  for (const auto& p : m.inputs) {
    if (!validName(p.name)) return bad("input name '" + p.name + "' " + kNameRule);
    if (!to_side.insert(p.name).second) return bad("two inputs are named '" + p.name + "'");
  }
  for (const auto& p : m.outputs) {
    if (!validName(p.name)) return bad("output name '" + p.name + "' " + kNameRule);
    if (!from_side.insert(p.name).second) return bad("two outputs are named '" + p.name + "'");
  }
  for (const auto& p : m.params) {
    if (!validName(p.name)) return bad("parameter name '" + p.name + "' " + kNameRule);
    if (!to_side.insert(p.name).second || !from_side.insert(p.name).second)
      return bad("parameter '" + p.name + "' has the name of another port or parameter");
    if (auto st = p.validate(p.default_value); !st) return bad("default value: " + st.message());
    if (p.shapes_interface && p.interactive)
      return bad("parameter '" + p.name + "' shapes the node's ports, so it cannot have ports itself");
  }
  for (const auto& s : m.slots) {
    if (!validName(s.name)) return bad("slot name '" + s.name + "' " + kNameRule);
    if (!to_side.insert(s.name).second) return bad("slot '" + s.name + "' has the name of another port");
    if (!s.handler) return bad("slot '" + s.name + "' has no handler");
  }
  for (const auto& t : m.triggers) {
    if (!validName(t.name)) return bad("trigger name '" + t.name + "' " + kNameRule);
    if (!from_side.insert(t.name).second) return bad("trigger '" + t.name + "' has the name of another port");
  }
  return Status::ok();
}

}  // namespace apex
