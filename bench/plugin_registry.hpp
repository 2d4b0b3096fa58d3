// The node types of the installed plugin libraries, as the runtime loads them,
// plus a benchmark's own types: made once per process.
#pragma once

#include <cstdio>
#include <functional>

#include "apex/core/registry.hpp"
#include "plugin_types.hpp"  // apex_runtime/src/ros

namespace apex_bench {

inline apex::NodeRegistry& pluginRegistry(const std::function<void(apex::NodeRegistry&)>& add_own) {
  static apex::NodeRegistry* r = [&] {
    auto* reg = new apex::NodeRegistry();
    static auto* types = new apex::ros_host::PluginTypes;  // never unloaded: node code lives in its libraries
    for (const auto& e : types->registerAll(*reg)) std::fprintf(stderr, "%s\n", e.c_str());
    add_own(*reg);
    return reg;
  }();
  return *r;
}

}  // namespace apex_bench
