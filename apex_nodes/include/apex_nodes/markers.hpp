// Clusters' boxes, a plane's outline, image regions' rays and keypoints for rviz: what MarkerPublisher (ros_io/markers.cpp, in
// apex_nodes_ros) publishes, built without ROS running so that tests check it.
#pragma once

#include <visualization_msgs/MarkerArray.h>

#include <cstddef>
#include <limits>
#include <string>

#include "apex/core/param.hpp"
#include "apex_nodes/cluster_features.hpp"
#include "apex_nodes/types.hpp"

namespace apex_nodes {

struct Keypoints;  // features.hpp

/** @brief How clusterMarkers draws. */
struct MarkerOptions {
  std::string ns = "clusters";  ///< the boxes' marker namespace; labels go in "<ns>/labels"
  bool oriented = false;  ///< the oriented boxes (PCA) instead of the axis-aligned ones
  bool labels = true;  ///< above each box, its label and point count
  apex::Color color{0, 255, 0};  ///< the boxes', 0..255
  double alpha = 0.5;  ///< the boxes' opacity, 0..1
  double lifetime = 0;  ///< seconds a marker stays without an update; 0: until replaced
  double text_height = 0.15;  ///< the labels' letter height, metres
  double ray_length = 2.0;  ///< regions' rays and projected boxes, keypoints: how far from the camera, metres
};

/** @brief For `last_count`: what the previous array drew is not known (the first one, or the
 *  options changed since): the array clears the display first. */
constexpr std::size_t kUnknownMarkerCount = std::numeric_limits<std::size_t>::max();

/** @brief Boxes (CUBE) for `features`' clusters, with their header: cluster i has id i in
 *  `options.ns`, its label (TEXT_VIEW_FACING, if `options.labels`) id i in "<ns>/labels". When
 *  there are fewer clusters than `last_count` (the previous array's), a DELETEALL comes first, so
 *  no box of the previous array stays. A cluster without points gets DELETEs for its ids instead.
 *  Scales are at least 0.001 m, so that flat clusters show. */
visualization_msgs::MarkerArray clusterMarkers(const ClusterFeatures& features, const MarkerOptions& options,
                                               std::size_t last_count);

/** @brief A plane's outline: the hull's points (ConvexHull's, in order round it) joined into a
 *  closed LINE_STRIP in the hull's frame, id 0 in "<ns>/plane", 1 cm wide, in `options.color`.
 *  Throws std::invalid_argument if the hull has fewer than 3 points or no x, y, z. */
visualization_msgs::Marker hullMarker(const Cloud& hull, const MarkerOptions& options);

/** @brief Regions of a camera's image in 3-D, for rviz: from the camera's origin a ray through
 *  each region's centroid, and the region's box projected to `options.ray_length` metres along
 *  the optical axis, all one LINE_LIST (id 0 in "<ns>/rays") in the regions' frame, which must be
 *  the camera's (its optical frame: x right, y down, z forward). The pixels are taken as the
 *  model's rectified image's (P): regions of a raw image go through UndistortRegions first.
 *  Throws std::invalid_argument naming the camera if the model is not calibrated. */
visualization_msgs::Marker regionRays(const Regions& regions, const sensor_msgs::CameraInfo& camera,
                                      const MarkerOptions& options);

/** @brief Keypoints of a camera's image in 3-D, for rviz: each keypoint where its ray from the
 *  camera reaches `options.ray_length` metres along the optical axis (the plane regionRays
 *  projects boxes to), all one POINTS marker (id 0 in "<ns>/keypoints", 1 cm points) in the
 *  keypoints' frame, which must be the camera's optical frame. Pixels as regionRays takes them
 *  (the rectified image's, P). Throws std::invalid_argument naming the camera if the model is not
 *  calibrated. */
visualization_msgs::Marker keypointPoints(const Keypoints& keypoints, const sensor_msgs::CameraInfo& camera,
                                          const MarkerOptions& options);

}  // namespace apex_nodes
