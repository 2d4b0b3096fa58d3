// Fills a NodeRegistry with every node type exported to APEX through pluginlib.
#pragma once

#include <pluginlib/class_loader.hpp>

#include <memory>
#include <string>
#include <vector>

#include "apex/core/registry.hpp"
#include "apex/ros/node_plugin.hpp"

namespace apex {
namespace ros_host {

class PluginTypes {
 public:
  /** @brief Finds plugins exported in package.xml files (<apex plugin="..."/>) and in
   *  `extra_xml` plugin description files. */
  explicit PluginTypes(std::vector<std::string> extra_xml = {});
  /** @brief Registers every type it can load; returns one message per type that
   *  failed, naming the type and its library, while the others load. */
  std::vector<std::string> registerAll(NodeRegistry& registry);

 private:
  std::string load(const std::unique_ptr<pluginlib::ClassLoader<NodePlugin>>& loader, const std::string& type,
                   NodeRegistry& registry);
  std::vector<std::unique_ptr<pluginlib::ClassLoader<NodePlugin>>> loaders_;
  std::vector<std::shared_ptr<NodePlugin>> plugins_;  // keep their libraries loaded
  std::vector<std::string> errors_;
};

}  // namespace ros_host
}  // namespace apex
