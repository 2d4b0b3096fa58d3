// The ROS header of the stamped types APEX's nodes exchange.
#pragma once

#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>

#include <optional>

#include "apex_nodes/cluster_features.hpp"
#include "apex_nodes/types.hpp"

APEX_TYPE_NAME(geometry_msgs::TransformStamped, "geometry_msgs/TransformStamped");
// Poses travel as the ROS messages themselves: one (e.g. an object's), or several in one frame.
APEX_TYPE_NAME(geometry_msgs::PoseStamped, "geometry_msgs/PoseStamped");
APEX_TYPE_NAME(geometry_msgs::PoseArray, "geometry_msgs/PoseArray");

namespace apex_nodes {

/** @brief The message's header, if it is an image, cloud, regions, clusters, cluster features, scan,
 *  camera model, transform or pose(s). */
inline std::optional<std_msgs::Header> headerOf(const apex::Message& m) {
  if (auto p = m.as<Image>()) return p->header;
  if (auto p = m.as<Cloud>()) return p->header;
  if (auto p = m.as<Regions>()) return p->header;
  if (auto p = m.as<Clusters>()) return p->header;
  if (auto p = m.as<ClusterFeatures>()) return p->header;
  if (auto p = m.as<sensor_msgs::LaserScan>()) return p->header;
  if (auto p = m.as<sensor_msgs::CameraInfo>()) return p->header;
  if (auto p = m.as<geometry_msgs::TransformStamped>()) return p->header;
  if (auto p = m.as<geometry_msgs::PoseStamped>()) return p->header;
  if (auto p = m.as<geometry_msgs::PoseArray>()) return p->header;
  return std::nullopt;
}

}  // namespace apex_nodes
