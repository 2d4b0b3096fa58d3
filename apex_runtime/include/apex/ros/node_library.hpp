// A library of node types as one pluginlib plugin. Each type registers itself
// next to its class, with the line a program uses too:
//   APEX_REGISTER_NODE(my_pkg::Gain, "my_pkg/Gain");
// and the library says once, in any one of its .cpp files:
//   APEX_NODE_LIBRARY(my_pkg_nodes)
// Its plugin XML has one entry per library, nothing per type:
//   <library path="lib/libmy_pkg_nodes">
//     <class type="apex_plugins::my_pkg_nodes" base_class_type="apex::NodeLibrary"/>
//   </library>
// exported in package.xml as <export><apex plugin="${prefix}/plugins.xml"/></export>.
#pragma once

#include <memory>
#include <vector>

#include "apex/core/registry.hpp"

namespace apex {

/** @brief What pluginlib creates, once per library: the node types it registered. A library one
 *  of whose types failed to register throws from types(), naming each failure: the host loads
 *  none of its types and says why. */
class NodeLibrary {
 public:
  virtual ~NodeLibrary() = default;
  virtual std::vector<std::shared_ptr<const NodeType>> types() const = 0;
};

}  // namespace apex

#include <pluginlib/class_list_macros.hpp>

/** Exports this library's APEX_REGISTER_NODE types as plugin apex_plugins::Name;
 *  once per library, at namespace scope, outside any namespace. */
#define APEX_NODE_LIBRARY(Name)                                                                                 \
  namespace apex_plugins {                                                                                      \
  class Name : public ::apex::NodeLibrary {                                                                     \
   public:                                                                                                      \
    std::vector<std::shared_ptr<const ::apex::NodeType>> types() const override {                               \
      return ::apex::detail::moduleTypesOrThrow(::apex::detail::moduleTypes(), ::apex::detail::moduleErrors()); \
    }                                                                                                           \
  };                                                                                                            \
  }                                                                                                             \
  PLUGINLIB_EXPORT_CLASS(apex_plugins::Name, apex::NodeLibrary)
