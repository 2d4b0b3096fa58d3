#include "plugin_types.hpp"

namespace apex {
namespace ros_host {

PluginTypes::PluginTypes(std::vector<std::string> extra_xml) {
  try {
    loaders_.push_back(std::make_unique<Loader>("apex", "apex::NodeLibrary"));
    if (!extra_xml.empty()) loaders_.push_back(std::make_unique<Loader>("apex", "apex::NodeLibrary", "plugin", extra_xml));
  } catch (const pluginlib::PluginlibException& e) {
    errors_.push_back(std::string("cannot search for APEX node libraries: ") + e.what() + " (is the devel space sourced?)");
  }
}

std::vector<std::string> PluginTypes::load(Loader& loader, const std::string& library, NodeRegistry& registry) {
  std::string where;
  try {
    where = "node library '" + library + "' ('" + loader.getClassLibraryPath(library) + "'): ";
  } catch (const pluginlib::PluginlibException&) {  // no such file: name the XML that declares it
    where = "node library '" + library + "' (declared in '" + loader.getPluginManifestPath(library) + "'): ";
  }
  std::vector<std::string> errors;
  try {
    std::shared_ptr<NodeLibrary> plugin = loader.createSharedInstance(library);
    const auto types = plugin->types();
    if (types.empty()) errors.push_back(where + "registers no node types (no APEX_REGISTER_NODE line in it)");
    for (const auto& type : types)
      if (auto st = registry.add(type); !st) errors.push_back(where + st.message());
    libraries_.push_back(std::move(plugin));
  } catch (const pluginlib::PluginlibException& e) {
    errors.push_back(where + e.what());
  } catch (const std::exception& e) {
    errors.push_back(where + "failed: " + e.what());
  }
  return errors;
}

std::vector<std::string> PluginTypes::registerAll(NodeRegistry& registry) {
  std::vector<std::string> errors = errors_;
  std::vector<std::string> seen;
  for (const auto& loader : loaders_) {
    for (const auto& library : loader->getDeclaredClasses()) {
      if (std::find(seen.begin(), seen.end(), library) != seen.end()) continue;  // listed by both loaders
      seen.push_back(library);
      for (auto& e : load(*loader, library, registry)) errors.push_back(std::move(e));
    }
  }
  return errors;
}

}  // namespace ros_host
}  // namespace apex
