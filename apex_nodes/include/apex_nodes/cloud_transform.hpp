// Moving clouds and merging them (cloud.hpp's clouds): x, y, z moved and normals turned in a copy of
// the bytes, every other field kept; several clouds as one, in one frame. TransformCloud, ICP, NDT
// and MergeClouds use them.
#pragma once

#include <geometry_msgs/Transform.h>
#include <ros/time.h>

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "apex_nodes/cloud.hpp"

namespace apex_nodes {

/** @brief The transform as a matrix that maps points of its child frame into its frame. */
Eigen::Affine3f toEigen(const geometry_msgs::Transform& t);
/** @brief The matrix (a rigid motion, e.g. a registration's result) as a ROS transform. */
geometry_msgs::Transform toTransform(const Eigen::Matrix4f& m);

/** @brief The points moved by `m`: x, y, z (float32, as requireField checks), and normal_x..z
 *  turned if the cloud has them as float32; every other field kept. Into `into` if given (e.g.
 *  Reused::next()), else new points. */
std::shared_ptr<Blob> transformPoints(const Blob& in, const Eigen::Affine3f& m, std::shared_ptr<Blob> into = nullptr);

/** @brief A cloud's points and the motion that takes them into the merged cloud's frame. */
struct PlacedPoints {
  std::shared_ptr<const Blob> points;
  Eigen::Affine3f pose = Eigen::Affine3f::Identity();
};

/** @brief The clouds, each moved by its pose, as one row of points in the order given. Fields:
 *  if every cloud has the first's layout (the same fields at the same offsets, the same
 *  point_step), that layout, every field kept; else the fields of the first that every cloud has
 *  (same name, datatype and count), packed in the first's order (PCL's padding "_" left out). Each cloud needs x, y and z as
 *  float32 (requireField). Dense if all are. Into `into` if given, else new points. Throws
 *  std::invalid_argument if `clouds` is empty. */
std::shared_ptr<Blob> mergePoints(const std::vector<PlacedPoints>& clouds, std::shared_ptr<Blob> into = nullptr);

/** @brief The motion that maps points of frame `source` into frame `target` at `stamp` (tf2's
 *  lookupTransform); throws if there is none. */
using TransformLookup =
    std::function<Eigen::Affine3f(const std::string& target, const std::string& source, const ros::Time& stamp)>;

/** @brief MergeClouds without ROS: the clouds (clouds[i] is input cloud_i) as one cloud in
 *  `frame`, each moved by `lookup` at its own stamp (a cloud already in `frame` is not looked up),
 *  stamped as the newest. An empty `frame`: every cloud must be in the same frame, which the result
 *  keeps. Empty clouds add no points and do not count for the fields; the others need x, y, z.
 *  Throws std::invalid_argument (frames differ, all clouds empty, a field missing) or
 *  std::runtime_error naming both frames and the stamp when `lookup` throws. The points go into
 *  `into` if given. */
std::shared_ptr<Cloud> mergeClouds(const std::vector<std::shared_ptr<const Cloud>>& clouds, const std::string& frame,
                                   const TransformLookup& lookup, std::shared_ptr<Blob> into = nullptr);

}  // namespace apex_nodes
