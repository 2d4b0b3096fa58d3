// Fills a NodeRegistry with the node types of every node library exported to APEX
// through pluginlib (one plugin per library: apex/ros/node_library.hpp).
#pragma once

#include <pluginlib/class_loader.hpp>

#include <memory>
#include <string>
#include <vector>

#include "apex/core/registry.hpp"
#include "apex/ros/node_library.hpp"

namespace apex {
namespace ros_host {

class PluginTypes {
 public:
  /** @brief Finds libraries exported in package.xml files (<apex plugin="..."/>) and in
   *  `extra_xml` plugin description files. */
  explicit PluginTypes(std::vector<std::string> extra_xml = {});
  /** @brief Registers every type of every library it can load; returns one message per
   *  library or type that failed, naming it and its library file, while the others load. */
  std::vector<std::string> registerAll(NodeRegistry& registry);

 private:
  using Loader = pluginlib::ClassLoader<NodeLibrary>;
  std::vector<std::string> load(Loader& loader, const std::string& library, NodeRegistry& registry);
  std::vector<std::unique_ptr<Loader>> loaders_;
  std::vector<std::shared_ptr<NodeLibrary>> libraries_;  // keep them loaded: node code lives there
  std::vector<std::string> errors_;
};

}  // namespace ros_host
}  // namespace apex
