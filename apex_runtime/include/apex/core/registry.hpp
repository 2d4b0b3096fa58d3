// Node types by id: manifest + factory. Filled by one line per type,
// APEX_REGISTER_NODE, next to the class in its .cpp: in a program, and in a
// plugin library that the ROS host loads (apex/ros/node_library.hpp).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <vector>

#include "apex/core/manifest.hpp"
#include "apex/core/node.hpp"
#include "apex/core/ports.hpp"
#include "apex/core/result.hpp"

namespace apex {

/** @brief A registered node type. */
struct NodeType {
  std::string id;  ///< e.g. "apex_nodes/GaussianBlur"
  std::shared_ptr<const Manifest> manifest;
  std::function<std::unique_ptr<Node>()> create;
};

namespace detail {
template <class T, class = void>
struct HasManifest : std::false_type {};
template <class T>
struct HasManifest<T, std::void_t<decltype(T::manifest())>> : std::is_convertible<decltype(T::manifest()), Manifest> {};

/** Compile-time checks of a node class, each saying how to fix it. */
template <class T>
struct NodeTypeChecks {
  static_assert(std::is_base_of_v<Node, T>, "APEX node types must derive from apex::Node");
  static_assert(!std::is_abstract_v<T>, "APEX node type is abstract: implement `void process() override`");
  static_assert(std::is_default_constructible_v<T>,
                "APEX node types need a default constructor: take settings as parameters in manifest()");
  static_assert(HasManifest<T>::value, "APEX node types declare their interface in `static apex::Manifest manifest()`");
  static constexpr bool value = true;
};
}  // namespace detail

/** @brief Up to `count` of `candidates` most like `name` (spelling, case, the part after a package
 *  prefix), closest first; none if none is close: for "did you mean ...?" in errors (node types,
 *  nodelet plugins). */
std::vector<std::string> closestNames(const std::string& name, const std::vector<std::string>& candidates, std::size_t count = 3);

class NodeRegistry {
 public:
  /** @brief Registers node class T under `id`. Fails on a duplicate id or an
   *  inconsistent manifest (clashing names, a default outside its range). */
  template <class T>
  Status add(const std::string& id) {
    static_assert(detail::NodeTypeChecks<T>::value, "see the messages above");
    return add(id, T::manifest(), [] { return std::unique_ptr<Node>(new T()); });
  }
  /** @brief Registers a type from a manifest and a factory. */
  Status add(const std::string& id, Manifest manifest, std::function<std::unique_ptr<Node>()> create);
  /** @brief Registers a type of another registry (checked there). Fails on a duplicate id. */
  Status add(std::shared_ptr<const NodeType> type);
  /** @brief Removes a type (e.g. its plugin library was unloaded); existing nodes keep working. */
  void remove(const std::string& id);

  /** @brief The type, or nullptr. */
  std::shared_ptr<const NodeType> find(const std::string& id) const;
  /** @brief The type a user means by `name`: its id, or a name without the package prefix that one
   *  type alone has ("GaussianBlur" for apex_nodes/GaussianBlur). Otherwise an error naming the
   *  closest ids ("did you mean ...?"), or the types that share the name. */
  Result<std::shared_ptr<const NodeType>> lookup(const std::string& name) const;
  /** @brief Up to `count` ids most like `name` (spelling, case, package prefix), closest first;
   *  none if no id is close. */
  std::vector<std::string> closest(const std::string& name, std::size_t count = 3) const;
  /** @brief Every type id, sorted. */
  std::vector<std::string> ids() const;
  /** @brief Every type, sorted by id. */
  std::vector<std::shared_ptr<const NodeType>> types() const;

  /** @brief The process-wide registry that APEX_REGISTER_NODE fills; never destroyed, so a
   *  library's types can leave it whenever the library goes, even at exit. */
  static NodeRegistry& global();
  /** @brief A registry holding a copy of every type in global(). */
  static NodeRegistry fromGlobal();

  NodeRegistry() = default;
  NodeRegistry(const NodeRegistry& other);
  NodeRegistry& operator=(const NodeRegistry&) = delete;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::shared_ptr<const NodeType>> types_;
};

namespace detail {
/** Registration from a static initialiser: prints the reason on failure. */
bool registerOrReport(const Status& status, const std::string& id);

/** The types registered by one module (the program, or a shared library). When a plugin
 *  library is unloaded, its types leave the process-wide registry with it: their factories
 *  are code of that library. */
class ModuleTypes {
 public:
  ModuleTypes() = default;
  ModuleTypes(const ModuleTypes&) = delete;
  ModuleTypes& operator=(const ModuleTypes&) = delete;
  ~ModuleTypes() {
    for (const auto& type : types.types())
      if (NodeRegistry::global().find(type->id) == type) NodeRegistry::global().remove(type->id);
  }
  NodeRegistry types;
};

/** This module's types: hidden, so every shared library has its own. A plugin library hands
 *  these to the host (APEX_NODE_LIBRARY). */
__attribute__((visibility("hidden"))) inline NodeRegistry& moduleTypes() {
  static ModuleTypes module;
  return module.types;
}

/** Why this module's types could not all be registered: a plugin library with any such error
 *  is refused as a whole when the host loads it (APEX_NODE_LIBRARY), naming them. */
__attribute__((visibility("hidden"))) inline std::vector<std::string>& moduleErrors() {
  static std::vector<std::string> errors;
  return errors;
}

/** The types of this module, or (a registration failed) an exception naming every failure. */
std::vector<std::shared_ptr<const NodeType>> moduleTypesOrThrow(const NodeRegistry& types,
                                                                const std::vector<std::string>& errors);

/** APEX_REGISTER_NODE: into the module's list and the process-wide registry. */
template <class T>
bool registerNode(const std::string& id) {
  static_assert(NodeTypeChecks<T>::value, "see the messages above");
  const Status status = moduleTypes().add<T>(id);
  if (!status) moduleErrors().push_back(status.message());
  const bool ok = registerOrReport(status, id);
  if (ok) registerOrReport(NodeRegistry::global().add(moduleTypes().find(id)), id);
  return ok;
}
}  // namespace detail

}  // namespace apex

#define APEX_CONCAT_INNER(a, b) a##b
#define APEX_CONCAT(a, b) APEX_CONCAT_INNER(a, b)
/** One line per node type, at namespace scope in its .cpp:
 *  APEX_REGISTER_NODE(my_pkg::Counter, "my_pkg/Counter");
 *  In a plugin library, that is all: APEX_NODE_LIBRARY (once per library) hands the
 *  library's types to the ROS host. */
#define APEX_REGISTER_NODE(Type, Id) \
  static const bool APEX_CONCAT(apex_registered_, __COUNTER__) = ::apex::detail::registerNode<Type>(Id)
