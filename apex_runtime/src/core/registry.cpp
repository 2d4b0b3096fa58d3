#include "apex/core/registry.hpp"

#include <iostream>

#include "names.hpp"

namespace apex {
namespace {

/** Every node has enable/disable slots and a processed trigger, first in their lists. */
Manifest withBuiltins(Manifest m) {
  m.slots.insert(m.slots.begin(), {EventSpec{kEnableSlot, "enables the node", [](Node&) {}},
                                   EventSpec{kDisableSlot, "disables the node: it sends Nothing", [](Node&) {}}});
  m.triggers.insert(m.triggers.begin(), EventSpec{kProcessedTrigger, "fires after each process()", nullptr});
  return m;
}

/** The ports an instance has with default parameters: what its typed handles must name. */
Manifest defaultInterface(const Manifest& type) {
  if (!type.shape) return type;
  ParamValues values;
  for (const auto& p : type.params) values.set(p.name, p.default_value);
  Manifest iface = type;
  try {
    if (type.shape(values, iface)) return iface;
  } catch (const std::exception&) {  // the graph reports it when a node is made
  }
  return type;
}

/** Makes one instance and resolves its typed handles (ports.hpp), so that a handle naming
 *  nothing is an error at registration, not at the first firing. */
Status checkHandles(const Manifest& type, const std::function<std::unique_ptr<Node>()>& create) {
  std::unique_ptr<Node> probe;
  try {
    probe = create();
  } catch (const std::exception& ex) {
    return Status::error(std::string("failed to construct: ") + ex.what());
  }
  if (!probe) return Status::error("its factory made no node");
  return detail::resolveHandles(*probe, defaultInterface(type));
}

}  // namespace

Status NodeRegistry::add(const std::string& id, Manifest manifest, std::function<std::unique_ptr<Node>()> create) {
  if (!validTypeId(id)) return Status::error("node type id '" + id + "' " + kTypeIdRule);
  if (!create) return Status::error("node type '" + id + "' has no factory");
  if (auto st = withBuiltins(manifest).check(); !st) return Status::error("node type '" + id + "': " + st.message());
  if (auto st = checkHandles(withBuiltins(manifest), create); !st) return Status::error("node type '" + id + "': " + st.message());
  auto type = std::make_shared<NodeType>(NodeType{id, std::make_shared<const Manifest>(withBuiltins(std::move(manifest))),
                                                  std::move(create)});
  std::lock_guard<std::mutex> lock(mutex_);
  if (!types_.emplace(id, std::move(type)).second) return Status::error("node type '" + id + "' is already registered");
  return Status::ok();
}

Status NodeRegistry::add(std::shared_ptr<const NodeType> type) {
  if (!type) return Status::error("no node type given");
  std::lock_guard<std::mutex> lock(mutex_);
  if (!types_.emplace(type->id, type).second) return Status::error("node type '" + type->id + "' is already registered");
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

std::vector<std::shared_ptr<const NodeType>> NodeRegistry::types() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::shared_ptr<const NodeType>> out;
  for (const auto& [id, type] : types_) out.push_back(type);
  return out;
}

NodeRegistry::NodeRegistry(const NodeRegistry& other) {
  std::lock_guard<std::mutex> lock(other.mutex_);
  types_ = other.types_;
}

NodeRegistry& NodeRegistry::global() {
  static auto* registry = new NodeRegistry();  // leaked on purpose: see the header
  return *registry;
}

NodeRegistry NodeRegistry::fromGlobal() { return NodeRegistry(global()); }

namespace detail {
bool registerOrReport(const Status& status, const std::string& id) {
  if (!status) std::cerr << "apex: cannot register node type '" << id << "': " << status.message() << std::endl;
  return status.isOk();
}
}  // namespace detail

}  // namespace apex
