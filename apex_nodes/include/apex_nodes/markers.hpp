// Clusters' boxes, a plane's outline, image regions' rays, tracked regions' paths and keypoints for rviz: what MarkerPublisher
// (ros_io/markers.cpp, in apex_nodes_ros) publishes, built without ROS running so that tests check it.
#pragma once

#include <visualization_msgs/MarkerArray.h>

#include <cstddef>
#include <deque>
#include <limits>
#include <map>
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
  int track_length = 30;  ///< TrackMarkers: the points a track keeps, and the frames it lives unseen
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

/** @brief The paths of regions that carry a track's id in `label` (MultiObjectTracker's), for
 *  rviz, kept from frame to frame. MarkerPublisher owns one (parameter `tracks`) and calls it from
 *  its thread group only. The options are expected to stay the same between reset()s:
 *  MarkerPublisher resets when one of its parameters changes. */
class TrackMarkers {
 public:
  /** @brief Adds one frame's regions to their tracks; returns what changed for rviz:
   *  - each region with a label >= 0 adds to the track of that id the middle of its box as
   *    regionRays draws the box: halfway between its corners (x, y) and (x + width, y + height),
   *    on the plane `options.ray_length` metres along the optical axis. A track keeps its last
   *    `options.track_length` points. A region without a label, or with an id met earlier in the
   *    same frame, adds nothing.
   *  - each track that got a point: a LINE_STRIP through its points, oldest first (id: the
   *    track's id, in "<ns>/tracks", 1 cm wide; only from its second point, as rviz refuses a
   *    strip of one), and a TEXT_VIEW_FACING "#<id>" at its newest point (same id, in
   *    "<ns>/tracks/ids", `options.text_height` high), both in the id's colour: a full hue, the
   *    same for an id in every frame and every TrackMarkers, far apart for consecutive ids.
   *  - a track without a point in `options.track_length` frames in a row is forgotten: DELETEs for
   *    its line and its text. One unseen for fewer frames stays as rviz last drew it.
   *  Everything carries the regions' header: the points are in the camera's optical frame, so a
   *  path shows how its object moved in the image (a camera that moves adds its own motion).
   *  Throws std::invalid_argument naming the camera if its model is not calibrated; nothing
   *  changes then. */
  visualization_msgs::MarkerArray update(const Regions& regions, const sensor_msgs::CameraInfo& camera,
                                         const MarkerOptions& options);

  /** @brief Forgets every track; returns DELETEs for the line and text of each (in the namespace
   *  and frame of the last update(), stamped 0 so that rviz takes them whenever they arrive), or
   *  an empty array if there was none. */
  visualization_msgs::MarkerArray reset();

 private:
  struct Track {
    std::deque<geometry_msgs::Point> points;  // oldest first
    std::size_t unseen = 0;  // frames in a row without a point
  };
  std::map<int, Track> tracks_;  // by id: arrays list them in id order
  std_msgs::Header header_;  // the last update's: reset() deletes in its frame
  MarkerOptions options_;  // the last update's: reset() deletes in its namespace
};

}  // namespace apex_nodes
