// What ClusterFeatures measures on each cluster of a Clusters message (types.hpp): where it is,
// how big, how it lies. For rviz (MarkerPublisher, markers.hpp) and for nodes that pick or track
// objects by size and position. Coordinates are in the clusters' frame (header.frame_id), metres.
#pragma once

#include <std_msgs/Header.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "apex/core/message.hpp"

namespace apex_nodes {

/** @brief A box that may be turned: its centre, its size along its own axes, and the rotation
 *  from its axes to the frame's (a proper rotation: x, y, z stay right-handed). */
struct OrientedBox {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d extent = Eigen::Vector3d::Zero();  ///< along the box's x (longest), y, z (shortest) axes
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

/** @brief One cluster's features, from its finite points (x, y, z all finite). A cluster with no
 *  finite point has `points` 0 and every vector zero (MarkerPublisher draws nothing for it). */
struct ClusterFeature {
  int label = -1;  ///< the cluster's index in its Clusters (0: the first, the largest from EuclideanClustering)
  std::size_t points = 0;  ///< finite points
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Vector3d min = Eigen::Vector3d::Zero();  ///< the axis-aligned box's lowest corner
  Eigen::Vector3d max = Eigen::Vector3d::Zero();  ///< ... and highest
  Eigen::Vector3d extent = Eigen::Vector3d::Zero();  ///< the axis-aligned box's size: max - min
  /** The box along the points' principal axes (PCA of their covariance): x along the largest
   *  spread. It is the tightest box only when the spreads differ (a cube's axes are any). */
  OrientedBox oriented;

  /** @brief The axis-aligned box's centre. */
  Eigen::Vector3d centre() const { return 0.5 * (min + max); }
};

/** @brief The features of each cluster of one Clusters message, in its order, with its header. */
struct ClusterFeatures {
  std_msgs::Header header;
  std::vector<ClusterFeature> clusters;
};

/** @brief The header as the next message in a chain should carry it. */
inline const std_msgs::Header& headerOf(const ClusterFeatures& f) { return f.header; }

}  // namespace apex_nodes

APEX_TYPE_NAME(apex_nodes::ClusterFeatures, "apex_nodes/ClusterFeatures");
