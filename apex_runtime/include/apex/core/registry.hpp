// Node types by id: manifest + factory. Filled by one line per type
// (APEX_REGISTER_NODE), or by pluginlib at the ROS edge.
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
struct HasManifest<T, std::void_t<decltype(T::manifest())>>
    : std::is_convertible<decltype(T::manifest()), Manifest> {};

/** Compile-time checks of a node class, each saying how to fix it. */
template <class T>
struct NodeTypeChecks {
  static_assert(std::is_base_of_v<Node, T>, "APEX node types must derive from apex::Node");
  static_assert(!std::is_abstract_v<T>, "APEX node type is abstract: implement `void process() override`");
  static_assert(std::is_default_constructible_v<T>,
                "APEX node types need a default constructor: take settings as parameters in manifest()");
  static_assert(HasManifest<T>::value,
                "APEX node types declare their interface in `static apex::Manifest manifest()`");
  static constexpr bool value = true;
};
}  // namespace detail

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
  /** @brief Removes a type (e.g. its plugin library was unloaded); existing nodes keep working. */
  void remove(const std::string& id);

  /** @brief The type, or nullptr. */
  std::shared_ptr<const NodeType> find(const std::string& id) const;
  /** @brief Every type id, sorted. */
  std::vector<std::string> ids() const;

  /** @brief The process-wide registry that APEX_REGISTER_NODE fills. */
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
}  // namespace detail

}  // namespace apex

#define APEX_CONCAT_INNER(a, b) a##b
#define APEX_CONCAT(a, b) APEX_CONCAT_INNER(a, b)
/** One line per node type, at namespace scope in its .cpp:
 *  APEX_REGISTER_NODE(my_pkg::Counter, "my_pkg/Counter"); */
#define APEX_REGISTER_NODE(Type, Id)                                        \
  static const bool APEX_CONCAT(apex_registered_, __COUNTER__) =             \
      ::apex::detail::registerOrReport(::apex::NodeRegistry::global().add<Type>(Id), Id)
