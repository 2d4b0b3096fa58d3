#include "apex/core/registry.hpp"

#include <iostream>
#include <set>

#include "names.hpp"

namespace apex {
namespace {

Status checkNames(const std::string& id, const Manifest& m) {
  auto bad = [&](const std::string& what) { return Status::error("node type '" + id + "': " + what); };
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

/** Every node has enable/disable slots and a processed trigger, first in their lists. */
Manifest withBuiltins(Manifest m) {
  m.slots.insert(m.slots.begin(), {EventSpec{kEnableSlot, "enables the node", [](Node&) {}},
                                   EventSpec{kDisableSlot, "disables the node: it sends Nothing", [](Node&) {}}});
  m.triggers.insert(m.triggers.begin(), EventSpec{kProcessedTrigger, "fires after each process()", nullptr});
  return m;
}

}  // namespace

Status NodeRegistry::add(const std::string& id, Manifest manifest, std::function<std::unique_ptr<Node>()> create) {
  if (!validTypeId(id)) return Status::error("node type id '" + id + "' " + kTypeIdRule);
  if (!create) return Status::error("node type '" + id + "' has no factory");
  auto st = checkNames(id, withBuiltins(manifest));
  if (!st) return st;
  auto type = std::make_shared<NodeType>(NodeType{id, std::make_shared<const Manifest>(withBuiltins(std::move(manifest))),
                                                  std::move(create)});
  std::lock_guard<std::mutex> lock(mutex_);
  if (!types_.emplace(id, std::move(type)).second) return Status::error("node type '" + id + "' is already registered");
  return Status::ok();
}

void NodeRegistry::remove(const std::string& id) {
  std::lock_guard<std::mutex> lock(mutex_);
  types_.erase(id);
}

std::shared_ptr<const NodeType> NodeRegistry::find(const std::string& id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = types_.find(id);
  return it == types_.end() ? nullptr : it->second;
}

std::vector<std::string> NodeRegistry::ids() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::string> out;
  for (const auto& [id, type] : types_) out.push_back(id);
  return out;
}

NodeRegistry::NodeRegistry(const NodeRegistry& other) {
  std::lock_guard<std::mutex> lock(other.mutex_);
  types_ = other.types_;
}

NodeRegistry& NodeRegistry::global() {
  static NodeRegistry registry;
  return registry;
}

NodeRegistry NodeRegistry::fromGlobal() { return NodeRegistry(global()); }

namespace detail {
bool registerOrReport(const Status& status, const std::string& id) {
  if (!status) std::cerr << "apex: cannot register node type '" << id << "': " << status.message() << std::endl;
  return status.isOk();
}
}  // namespace detail

}  // namespace apex
