// What point-cloud nodes do with a cloud (types.hpp): it keeps every field its sensor sent, so
// a node computes on an x, y, z view of it and publishes whole points, selected by index with
// every field; the fields it does not know pass through. docs/architecture.md says why.
#pragma once

#include <pcl/PCLPointCloud2.h>
#include <pcl/PointIndices.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/conversions.h>

#include <cstring>
#include <memory>
#include <type_traits>
#include <string>
#include <vector>

#include "apex_nodes/output_buffer.hpp"
#include "apex_nodes/types.hpp"

namespace apex_nodes {

using Blob = pcl::PCLPointCloud2;
using XyzCloud = pcl::PointCloud<pcl::PointXYZ>;

/** @brief Bytes of one value of a PointField datatype (pcl::PCLPointField::FLOAT32...); 0 if unknown. */
std::uint32_t valueBytes(std::uint8_t datatype);
/** @brief width x height. */
std::size_t pointCount(const Cloud& cloud);
/** @brief The names of the cloud's fields, e.g. "x, y, z, rgb", for messages. */
std::string fieldNames(const Blob& points);
bool hasField(const Blob& points, const std::string& name);
/** @brief Throws std::invalid_argument naming the field, the cloud and the fields it has,
 *  unless the cloud has `field` (one of x, y, z: as float32). */
void requireField(const Cloud& cloud, const std::string& field);
/** @brief Throws std::invalid_argument naming the flaw unless the layout is sound: sizes that fit
 *  the data, known datatypes, fields within a point, little-endian, x, y and z present. For
 *  clouds from outside (topics, bags): nodes may then read any point. */
void checkCloud(const Cloud& cloud);
/** @brief Throws std::invalid_argument if the cloud lacks x, y or z, is empty, or has no finite
 *  point (it reads up to the first finite one). For a node that needs points. */
void requirePoints(const Cloud& cloud);

/** @brief The points' x, y, z, organised as the cloud is, once requirePoints passes; into `into`
 *  if given (e.g. Reused::next()), else a new cloud. */
std::shared_ptr<const XyzCloud> xyzOf(const Cloud& cloud, std::shared_ptr<XyzCloud> into = nullptr);
/** @brief The points' x, y, z into `xyz`, as pcl::fromPCLPointCloud2 gives them (organised as the
 *  points, each one's fourth float 1), reusing its memory; no check beyond requireField's for x, y, z. */
void copyXyz(const Blob& points, XyzCloud& xyz);
/** @brief Where a point's x, y and z lie in its bytes (float32, requireField's fields). */
struct XyzOffsets {
  std::uint32_t x = 0, y = 4, z = 8;
  /** One after another, as nearly every sensor and PCL lay them out: one read of 12 bytes. */
  bool packed() const { return y == x + 4 && z == x + 8; }
};
/** @brief The offsets of x, y and z in `points` (which has them: requireField). */
XyzOffsets xyzOffsets(const Blob& points);
/** @brief Calls f(x, y, z) for each point, row by row, reading them where they lie (no copy: for a
 *  node that only reads the points once or twice, cheaper than xyzOf's view). */
template <class F>
void forEachXyz(const Blob& points, F&& f) {
  const XyzOffsets at = xyzOffsets(points);
  const auto rows = [&](auto packed) {
    for (std::size_t row = 0; row < points.height; ++row) {
      const std::uint8_t* from = points.data.data() + row * points.row_step;
      for (std::size_t col = 0; col < points.width; ++col, from += points.point_step) {
        float v[3];
        if constexpr (decltype(packed)::value) {
          std::memcpy(v, from + at.x, sizeof v);
        } else {
          std::memcpy(&v[0], from + at.x, sizeof(float));
          std::memcpy(&v[1], from + at.y, sizeof(float));
          std::memcpy(&v[2], from + at.z, sizeof(float));
        }
        f(v[0], v[1], v[2]);
      }
    }
  };
  if (at.packed()) rows(std::true_type());
  else rows(std::false_type());
}
/** @brief The points at `indices`, whole (every field), as one row; into `into` if given (every
 *  member set), else new points. */
std::shared_ptr<Blob> selectPoints(const Blob& points, const pcl::Indices& indices, std::shared_ptr<Blob> into = nullptr);
/** @brief Every index below `count` that `indices` (ascending) lacks. */
pcl::Indices complement(const pcl::Indices& indices, std::size_t count);
/** @brief The clusters a PCL segmentation found in `in` (each its points' indices), each point whole,
 *  largest first (equal sizes in the order found), with `in`'s header. */
std::shared_ptr<Clusters> clustersOf(const Cloud& in, std::vector<pcl::PointIndices> found);
/** @brief A result: `points` with the header of the cloud it came from. */
std::shared_ptr<Cloud> cloudResult(const Cloud& in, std::shared_ptr<const Blob> points);

/** @brief A typed PCL cloud as a cloud's points (its fields named as PCL names them). */
template <class PointT>
std::shared_ptr<Blob> toBlob(const pcl::PointCloud<PointT>& typed) {
  auto out = std::make_shared<Blob>();
  pcl::toPCLPointCloud2(typed, *out);
  return out;
}
/** @brief A cloud with `header` holding `typed`: for tests and for sources that make points. */
template <class PointT>
std::shared_ptr<Cloud> makeCloud(const std_msgs::Header& header, const pcl::PointCloud<PointT>& typed) {
  auto out = std::make_shared<Cloud>();
  out->header = header;
  out->points = toBlob(typed);
  return out;
}
/** @brief The points as a typed PCL cloud (fields the type lacks are dropped, ones the cloud
 *  lacks stay zero: check with hasField first). */
template <class PointT>
pcl::PointCloud<PointT> typedPoints(const Cloud& cloud) {
  pcl::PointCloud<PointT> out;
  if (cloud.points && pointCount(cloud) > 0) pcl::fromPCLPointCloud2(*cloud.points, out);
  return out;
}

}  // namespace apex_nodes
