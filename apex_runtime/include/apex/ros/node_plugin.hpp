// Node types as pluginlib plugins: one line per type in its .cpp,
//   APEX_EXPORT_NODE(apex_nodes, GaussianBlur, apex_nodes::GaussianBlur)
// and one entry in the package's plugin XML,
//   <class name="apex_nodes/GaussianBlur" type="apex_plugins::apex_nodes::GaussianBlur"
//          base_class_type="apex::NodePlugin"/>
// exported in package.xml as <export><apex plugin="${prefix}/plugins.xml"/></export>.
#pragma once

#include <memory>
#include <string>

#include "apex/core/registry.hpp"

namespace apex {

/** @brief What pluginlib creates: a node type's id, manifest and factory. */
class NodePlugin {
 public:
  virtual ~NodePlugin() = default;
  virtual std::string id() const = 0;
  virtual Manifest manifest() const = 0;
  virtual std::unique_ptr<Node> create() const = 0;
};

template <class T>
class NodePluginFor : public NodePlugin {
  static_assert(detail::NodeTypeChecks<T>::value, "see the messages above");

 public:
  Manifest manifest() const override { return T::manifest(); }
  std::unique_ptr<Node> create() const override { return std::unique_ptr<Node>(new T()); }
};

}  // namespace apex

#include <pluginlib/class_list_macros.hpp>

/** Exports node class Type as plugin "Package/Name"; at namespace scope, outside any namespace.
 *  (Type is named through a global alias first: inside apex_plugins::Package, a
 *  name like Package::Foo would find the plugin's own namespace.) */
#define APEX_EXPORT_NODE(Package, Name, Type)                                   \
  using apex_exported_##Package##_##Name = Type;                                \
  namespace apex_plugins {                                                      \
  namespace Package {                                                           \
  class Name : public ::apex::NodePluginFor<::apex_exported_##Package##_##Name> { \
   public:                                                                      \
    std::string id() const override { return #Package "/" #Name; }            \
  };                                                                            \
  }                                                                             \
  }                                                                             \
  PLUGINLIB_EXPORT_CLASS(apex_plugins::Package::Name, apex::NodePlugin)
