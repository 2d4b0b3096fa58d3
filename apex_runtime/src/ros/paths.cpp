#include "paths.hpp"

#include <ros/package.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "apex/core/node_names.hpp"

namespace apex {
namespace ros_host {
namespace {

/** ~file_roots: a list of folders, or one string "a:b" (as ROS_PACKAGE_PATH). */
std::vector<std::string> configuredRoots(const ros::NodeHandle& pnh) {
  std::vector<std::string> list;
  XmlRpc::XmlRpcValue value;
  if (!pnh.getParam("file_roots", value)) return list;
  if (value.getType() == XmlRpc::XmlRpcValue::TypeString) {
    std::stringstream text(static_cast<std::string>(value));
    for (std::string folder; std::getline(text, folder, ':');)
      if (!folder.empty()) list.push_back(folder);
  } else if (value.getType() == XmlRpc::XmlRpcValue::TypeArray) {
    for (int i = 0; i < value.size(); ++i)
      if (value[i].getType() == XmlRpc::XmlRpcValue::TypeString) list.push_back(static_cast<std::string>(value[i]));
      else ROS_ERROR_STREAM_NAMED("apex", "~file_roots: entry " << i << " is not a folder name; left out");
  } else {
    ROS_ERROR_STREAM_NAMED("apex", "~file_roots must be a list of folders, or folders separated by ':'");
  }
  return list;
}

}  // namespace

std::string ownFolder() {
  const char* ros_home = std::getenv("ROS_HOME");
  const char* home = std::getenv("HOME");
  const std::string folder = (ros_home && *ros_home ? std::string(ros_home) : std::string(home ? home : "") + "/.ros") + "/apex";
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  return folder;
}

std::string packagePath(const std::string& package) { return ros::package::getPath(package); }

std::string yamlQuoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

FileRoots launchRoots(const ros::NodeHandle& pnh, const LaunchFolders& launch) {
  std::vector<std::string> writable = configuredRoots(pnh);
  writable.push_back(ownFolder());
  writable.insert(writable.end(), launch.writable.begin(), launch.writable.end());
  std::vector<std::string> read_only = launch.read_only;
  if (const std::string package = packagePath("apex"); !package.empty()) read_only.push_back(package + "/graphs");
  const std::string param = pnh.resolveName("file_roots");
  return FileRoots(writable, packagePath).readOnly(read_only).hint([param](const std::string& folder) {
    return "; to allow it, add its folder to the parameter " + param + " (roslaunch apex runtime.launch file_roots:=" + folder +
           ")";
  });
}

std::shared_ptr<const Manifest> specOf(const NodeRegistry& types, const NodeDescription& d, const std::string& param) {
  if (!d.subgraph) {
    const auto type = types.find(d.type);
    return type ? type->manifest : nullptr;
  }
  for (const auto& e : d.subgraph->exports) {
    if (e.kind != ExportDescription::Kind::Parameter || e.name != param) continue;
    const std::string& inner = e.inner.front();
    const auto slash = inner.rfind('/');
    if (const NodeDescription* n = findNode(*d.subgraph, inner.substr(0, slash))) {
      auto m = specOf(types, *n, inner.substr(slash + 1));
      if (!m || !m->findParam(inner.substr(slash + 1))) return nullptr;
      auto renamed = std::make_shared<Manifest>();
      renamed->params.push_back(*m->findParam(inner.substr(slash + 1)));
      renamed->params.back().name = param;
      return renamed;
    }
  }
  return nullptr;
}

Result<std::string> pathValue(const std::shared_ptr<const Manifest>& iface, const std::string& node, const std::string& param,
                              const std::string& text, const FileRoots& roots, bool confined) {
  const ParamSpec* spec = iface ? iface->findParam(param) : nullptr;
  if (!spec || spec->kind != ParamKind::Path) return text;  // the graph names the unknown node, type or parameter
  auto value = spec->parse(text);
  if (!value || std::get<std::string>(value.value()).empty()) return text;  // the graph says why / nothing to open
  const std::string& path = std::get<std::string>(value.value());
  auto resolved = confined ? roots.check(path, spec->path_mode) : FileRoots::anywhere(packagePath).resolve(path);
  if (!resolved) return Status::error(nodeLabel(node) + ": parameter '" + param + "': " + resolved.message());
  return yamlQuoted(resolved.value());
}

Status resolvePaths(const NodeRegistry& types, NodeDescription& d, const FileRoots& roots, bool confined) {
  for (auto& [param, text] : d.parameters) {
    auto value = pathValue(specOf(types, d, param), d.name, param, text, roots, confined);
    if (!value) return value.status();
    text = value.value();
  }
  return Status::ok();
}

void pathFolders(const NodeRegistry& types, const GraphDescription& g, LaunchFolders& folders) {
  for (const auto& d : g.nodes) {
    if (d.subgraph) pathFolders(types, *d.subgraph, folders);
    for (const auto& [param, text] : d.parameters) {
      const auto iface = specOf(types, d, param);
      const ParamSpec* spec = iface ? iface->findParam(param) : nullptr;
      if (!spec || spec->kind != ParamKind::Path) continue;
      auto value = spec->parse(text);
      const std::string path = value ? std::get<std::string>(value.value()) : "";
      if (path.empty()) continue;
      const bool folder_itself = spec->path_mode == PathMode::Directory ||
                                 (spec->path_mode == PathMode::ReadFileOrFolder && std::filesystem::is_directory(path));
      const std::string folder = folder_itself ? path : std::filesystem::path(path).parent_path().string();
      const bool reads = spec->path_mode == PathMode::Read || spec->path_mode == PathMode::ReadFileOrFolder;
      (reads ? folders.read_only : folders.writable).push_back(folder);
    }
  }
}

}  // namespace ros_host
}  // namespace apex
