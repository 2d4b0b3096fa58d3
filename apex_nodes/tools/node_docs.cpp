// Writes docs/nodes.md from the node types' manifests (scripts/node_docs runs it):
//   apex_node_docs [OUTPUT]
// Loads every node library the runtime loads, through pluginlib as the runtime does (no ROS master
// needed; the devel space must be sourced so that pluginlib finds APEX's plugins.xml), and writes
// the Markdown of node_docs.hpp to OUTPUT (atomically: a reader sees the old file or the new one)
// or to stdout. A library that fails to load is an error: the file would miss its types.
#include <iostream>
#include <string>

#include "apex/core/graph_file.hpp"  // writeFileAtomically
#include "node_docs.hpp"
#include "plugin_types.hpp"  // apex_runtime/src/ros

int main(int argc, char** argv) {
  if (argc > 2 || (argc == 2 && (std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help"))) {
    std::cerr << "usage: apex_node_docs [OUTPUT]   (Markdown of every APEX node type; stdout without OUTPUT)\n";
    return argc > 2 ? 2 : 0;
  }
  // Never unloaded (as in the runtime's tests): the types' code lives in the libraries, and the
  // registry holds it until the process ends.
  static auto* plugins = new apex::ros_host::PluginTypes;
  apex::NodeRegistry registry;
  const auto errors = plugins->registerAll(registry);
  for (const auto& e : errors) std::cerr << "apex_node_docs: " << e << "\n";
  if (!errors.empty()) {
    std::cerr << "apex_node_docs: not written: a node library failed to load\n";
    return 1;
  }
  const std::string text = apex_node_docs::nodeDocs(registry);
  if (argc < 2) {
    std::cout << text << std::flush;
    return std::cout ? 0 : 1;
  }
  if (auto st = apex::writeFileAtomically(argv[1], text); !st) {
    std::cerr << "apex_node_docs: " << st.message() << "\n";
    return 1;
  }
  return 0;
}
