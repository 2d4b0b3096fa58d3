#include "apex/core/manifest.hpp"

namespace apex {
namespace {

template <class T>
const T* find(const std::vector<T>& items, const std::string& name) {
  for (const auto& i : items) if (i.name == name) return &i;
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

}  // namespace apex
