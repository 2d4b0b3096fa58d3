#include "apex/core/registry.hpp"

#include <algorithm>
#include <cctype>
#include <iostream>
#include <stdexcept>

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
  if (auto st = checkHandles(withBuiltins(manifest), create); !st)
    return Status::error("node type '" + id + "': " + st.message());
  auto type = std::make_shared<NodeType>(
      NodeType{id, std::make_shared<const Manifest>(withBuiltins(std::move(manifest))), std::move(create)});
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

namespace {

std::string shortName(const std::string& id) { return id.substr(id.rfind('/') + 1); }

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/** Edits (insert, delete, replace) from a to b. */
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

Result<std::shared_ptr<const NodeType>> NodeRegistry::lookup(const std::string& name) const {
  if (auto exact = find(name)) return exact;
  std::vector<std::shared_ptr<const NodeType>> same;
  if (name.find('/') == std::string::npos)
    for (const auto& type : types())
      if (shortName(type->id) == name) same.push_back(type);
  if (same.size() == 1) return same.front();
  std::string message = "unknown node type '" + name + "'";
  if (same.size() > 1) {
    message = "node type '" + name + "' is ambiguous: ";
    for (std::size_t i = 0; i < same.size(); ++i) message += (i ? " or " : "") + same[i]->id;
    return Status::error(message + "; give the whole id");
  }
  const auto near = closest(name);
  if (!near.empty()) {
    message += ": did you mean ";
    for (std::size_t i = 0; i < near.size(); ++i) message += (i ? (i + 1 == near.size() ? " or " : ", ") : "") + near[i];
    message += "?";
  }
  const std::size_t known = ids().size();
  return Status::error(message + " (" + (known ? "list_node_types lists all " + std::to_string(known) : "no type is registered") +
                       ")");
}

std::vector<std::string> closestNames(const std::string& name, const std::vector<std::string>& candidates, std::size_t count) {
  // A substring of a name ("Blur") ranks with one edit; beyond a third of the name's length in
  // edits, a name is not close.
  const std::string wanted = lower(shortName(name));
  if (wanted.size() > kMaxNameLength) return {};  // no name is that long: nothing is close
  std::vector<std::pair<std::size_t, std::string>> scored;
  for (const auto& id : candidates) {
    const std::string candidate = lower(shortName(id));
    std::size_t d = editDistance(wanted, candidate);
    if (wanted.size() >= 3 && candidate.find(wanted) != std::string::npos) d = std::min<std::size_t>(d, 1);
    if (d <= std::max<std::size_t>(1, std::max(wanted.size(), candidate.size()) / 3)) scored.emplace_back(d, id);
  }
  std::sort(scored.begin(), scored.end());
  std::vector<std::string> out;
  for (std::size_t i = 0; i < scored.size() && i < count; ++i) out.push_back(scored[i].second);
  return out;
}

std::vector<std::string> NodeRegistry::closest(const std::string& name, std::size_t count) const {
  return closestNames(name, ids(), count);
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
std::vector<std::shared_ptr<const NodeType>> moduleTypesOrThrow(const NodeRegistry& types,
                                                                const std::vector<std::string>& errors) {
  if (errors.empty()) return types.types();
  std::string text = std::to_string(errors.size()) + " of its node types failed to register, so none is loaded: ";
  for (std::size_t i = 0; i < errors.size(); ++i) text += (i ? "; " : "") + errors[i];
  throw std::runtime_error(text);
}

bool registerOrReport(const Status& status, const std::string& id) {
  if (!status) std::cerr << "apex: cannot register node type '" << id << "': " << status.message() << std::endl;
  return status.isOk();
}
}  // namespace detail

}  // namespace apex
