// The image library's results as ROS messages (this package's msg/: apex/Regions, apex/Contours,
// ...): what ~inspect, `rostopic echo`, BagWriter and ResultPublisher send for them (their
// inspectors are registered in ros_io/inspectors.cpp). Each message keeps the result's header and
// image size; the conversions copy every field and never throw.
#pragma once

#include <apex/ChessboardCorners.h>
#include <apex/Circles.h>
#include <apex/Contours.h>
#include <apex/FiducialMarkers.h>
#include <apex/Homography.h>
#include <apex/Keypoints.h>
#include <apex/LineSegments.h>
#include <apex/Matches.h>
#include <apex/Regions.h>
#include <apex/Tracks.h>

#include "apex_nodes/features.hpp"
#include "apex_nodes/shapes.hpp"
#include "apex_nodes/types.hpp"

namespace apex_nodes {

/** @brief Boxes, areas, centroids, labels and confidences, with the header and image size. */
apex::Regions toRos(const Regions& regions);
/** @brief Regions as a recording holds them (BagReader's playback): the inverse of toRos. */
Regions fromRos(const apex::Regions& msg);
/** @brief Each contour's points as x and y; the hierarchy as 4 numbers per contour. */
apex::Contours toRos(const Contours& contours);
apex::LineSegments toRos(const Lines& lines);
apex::Circles toRos(const Circles& circles);
/** @brief Ids and corners per marker; with a camera model, each marker's pose (its rvec as a
 *  quaternion, its tvec as the position), for as many markers as there are rvec and tvec pairs. */
apex::FiducialMarkers toRos(const Markers& markers);
apex::ChessboardCorners toRos(const Corners& corners);
/** @brief The keypoints as cv::KeyPoint has them; 8-bit descriptors as descriptors_binary, any
 *  other depth as descriptors_float (converted to 32-bit floats), row by row. */
apex::Keypoints toRos(const Keypoints& keypoints);
/** @brief The matches with both sets of keypoints (empty where the Matches have none). */
apex::Matches toRos(const Matches& matches);
/** @brief found: the matrix is 3x3 (then it is copied row by row as doubles); else zeros. */
apex::Homography toRos(const Homography& homography);
apex::Tracks toRos(const Tracks& tracks);

}  // namespace apex_nodes
