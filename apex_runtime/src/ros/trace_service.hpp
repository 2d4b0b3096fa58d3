// ~trace (FrameTrace.srv): the frame trace turned on and off, and saved as Chrome trace event JSON.
#pragma once

#include <ros/ros.h>

#include "apex/core/file_roots.hpp"
#include "apex/core/graph.hpp"

namespace apex {
namespace ros_host {

/** @brief Serves ~trace for `graph`: start, stop, status, and save into a file `roots` allow
 *  (read when a request comes: the roots may be set after this). `process` names the trace's
 *  process track (the runtime's node name). */
ros::ServiceServer serveTrace(ros::NodeHandle& pnh, Graph& graph, const FileRoots& roots, std::string process);

}  // namespace ros_host
}  // namespace apex
