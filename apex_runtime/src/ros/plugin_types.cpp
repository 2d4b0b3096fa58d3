#include "plugin_types.hpp"

namespace apex {
namespace ros_host {

PluginTypes::PluginTypes(std::vector<std::string> extra_xml) {
  try {
    loaders_.push_back(std::make_unique<pluginlib::ClassLoader<NodePlugin>>("apex", "apex::NodePlugin"));
    if (!extra_xml.empty())
      loaders_.push_back(
          std::make_unique<pluginlib::ClassLoader<NodePlugin>>("apex", "apex::NodePlugin", "plugin", extra_xml));
  } catch (const pluginlib::PluginlibException& e) {
    errors_.push_back(std::string("cannot search for APEX node types: ") + e.what() +
                      " (is the devel space sourced?)");
  }
}

std::string PluginTypes::load(const std::unique_ptr<pluginlib::ClassLoader<NodePlugin>>& loader,
                              const std::string& type, NodeRegistry& registry) {
  std::string where;
  try {
    where = "node type '" + type + "' (library '" + loader->getClassLibraryPath(type) + "'): ";
  } catch (const pluginlib::PluginlibException&) {  // no such library: name the XML that declares it
    where = "node type '" + type + "' (declared in '" + loader->getPluginManifestPath(type) + "'): ";
  }
  try {
    std::shared_ptr<NodePlugin> plugin = loader->createSharedInstance(type);
    if (plugin->id() != type)
      return where + "the plugin calls itself '" + plugin->id() + "'; the plugin XML and APEX_EXPORT_NODE disagree";
    auto st = registry.add(type, plugin->manifest(), [plugin] { return plugin->create(); });
    plugins_.push_back(std::move(plugin));
    return st ? "" : where + st.message();
  } catch (const pluginlib::PluginlibException& e) {
    return where + e.what();
  } catch (const std::exception& e) {
    return where + "failed: " + e.what();
  }
}

std::vector<std::string> PluginTypes::registerAll(NodeRegistry& registry) {
  std::vector<std::string> errors = errors_;
  for (const auto& loader : loaders_) {
    for (const auto& type : loader->getDeclaredClasses()) {
      if (registry.find(type)) continue;  // listed by more than one loader
      const std::string error = load(loader, type, registry);
      if (!error.empty()) errors.push_back(error);
    }
  }
  return errors;
}

}  // namespace ros_host
}  // namespace apex
