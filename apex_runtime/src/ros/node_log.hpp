// The log lines of a graph's nodes go to rosconsole under a logger per node: ros.apex.<path>,
// a subgraph's '/' as '.', so `rosconsole set /apex ros.apex.camera_detector.threshold debug`
// (or rqt_logger_level) changes one node, and ros.apex.camera_detector the nodes inside it.
#pragma once

#include <ros/ros.h>

#include <string>
#include <vector>

namespace apex {
namespace ros_host {

/** @brief The rosconsole logger of a node: "threshold" -> "ros.apex.threshold". */
std::string nodeLoggerName(const std::string& node_path);
/** @brief Routes apex's log (apex/core/log.hpp) to rosconsole: a node's lines to its logger. */
void installRosconsoleSink();

/** @brief Serves the node's `~get_loggers` and `~set_logger_level` (what rqt_logger_level and
 *  `rosconsole` call) with log4cxx directly, in place of roscpp's own: on Debian 12, rosconsole's
 *  get_loggers (built against log4cxx 1.0) frees the logger hierarchy, and the next log line or
 *  level change crashes the process, whatever node it is. Only where `pnh` is the process's own
 *  private namespace (the standalone runtime; a nodelet's manager keeps its services). The
 *  returned servers must live as long as the runtime. */
std::vector<ros::ServiceServer> serveLoggerServices(ros::NodeHandle& pnh);

}  // namespace ros_host
}  // namespace apex
