// The ROS header of the stamped types APEX's nodes exchange.
#pragma once

#include <geometry_msgs/TransformStamped.h>

#include <optional>

#include "apex_nodes/cluster_features.hpp"
#include "apex_nodes/types.hpp"

APEX_TYPE_NAME(geometry_msgs::TransformStamped, "geometry_msgs/TransformStamped");

namespace apex_nodes {

/** @brief The message's header, if it is an image, cloud, regions, clusters, cluster features, scan,
 *  camera model or transform. */
inline std::optional<std_msgs::Header> headerOf(const apex::Message& m) {
  if (auto p = m.as<Image>()) return p->header;
  if (auto p = m.as<Cloud>()) return p->header;
  if (auto p = m.as<Regions>()) return p->header;
  if (auto p = m.as<Clusters>()) return p->header;
  if (auto p = m.as<ClusterFeatures>()) return p->header;
  if (auto p = m.as<sensor_msgs::LaserScan>()) return p->header;
  if (auto p = m.as<sensor_msgs::CameraInfo>()) return p->header;
  if (auto p = m.as<geometry_msgs::TransformStamped>()) return p->header;
  return std::nullopt;
}

}  // namespace apex_nodes
