// Paths from outside the process: the folders service calls may name (the runtime's file roots,
// as its launch sets them) and the values of path parameters.
#pragma once

#include <ros/node_handle.h>

#include <memory>
#include <string>
#include <vector>

#include "apex/core/file_roots.hpp"
#include "apex/core/graph_file.hpp"
#include "apex/core/registry.hpp"

namespace apex {
namespace ros_host {

/** @brief package:// and $(find pkg) through rospack, as everywhere in ROS. */
std::string packagePath(const std::string& package);

/** @brief $ROS_HOME/apex, or ~/.ros/apex (roscpp has no call for ROS_HOME; rospkg reads the
 *  same variable): the runtime's own folder, made if missing. */
std::string ownFolder();

/** @brief The folders of what a runtime's launch named: the graph's and those of files to write
 *  (writable), those of files only read, such as a bag (read only: a bag in ~ must not make all of
 *  ~ writable). */
struct LaunchFolders {
  std::vector<std::string> writable, read_only;
};

/** @brief The roots of a runtime: the folders in ~file_roots first (a list, or one string of
 *  folders separated by ':'; the first takes relative paths), then $ROS_HOME/apex (made if
 *  missing), then the launch's folders; the apex package's graphs/ may be read, never written. A
 *  refusal names ~file_roots by its full name and the runtime.launch argument that adds the folder. */
FileRoots launchRoots(const ros::NodeHandle& pnh, const LaunchFolders& launch);

/** @brief What a node's parameter is declared as: its type's, or for a subgraph the inner
 *  parameter its export stands for. nullptr if unknown. */
std::shared_ptr<const Manifest> specOf(const NodeRegistry& types, const NodeDescription& d, const std::string& param);

/** @brief A parameter's value as it is to be set: a path parameter's resolved, as YAML text.
 *  `confined` (from a service): inside `roots` and what its mode needs (a bag to read must exist),
 *  else an error naming node and parameter. Trusted (the launch's): `~`, package:// and $(find)
 *  expanded wherever the file is. Other parameters, and values the node will refuse, as given. */
Result<std::string> pathValue(const std::shared_ptr<const Manifest>& iface, const std::string& node, const std::string& param,
                              const std::string& text, const FileRoots& roots, bool confined);

/** @brief pathValue() for every parameter of a description. */
Status resolvePaths(const NodeRegistry& types, NodeDescription& d, const FileRoots& roots, bool confined);

/** @brief The folders the path parameters of a graph name (a folder parameter's own value), also
 *  inside subgraphs, by what the parameter does: the start-up graph's, after ~overrides, are the
 *  launch's roots. */
void pathFolders(const NodeRegistry& types, const GraphDescription& g, LaunchFolders& folders);

/** @brief A string as YAML text that reads back as that string. */
std::string yamlQuoted(const std::string& s);

}  // namespace ros_host
}  // namespace apex
