// Checks point-cloud nodes make on their input, and a result with its header.
#pragma once

#include <cmath>
#include <stdexcept>

#include "apex_nodes/types.hpp"

namespace apex_nodes {

/** @brief Throws std::invalid_argument if the cloud is empty or has no finite point. */
inline void requirePoints(const Cloud& in) {
  if (!in.points || in.points->empty()) throw std::invalid_argument("received an empty point cloud");
  for (const auto& p : *in.points)
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) return;
  throw std::invalid_argument("received a cloud of " + std::to_string(in.points->size()) + " points, none of them finite");
}

inline std::shared_ptr<Cloud> cloudResult(const Cloud& in, std::shared_ptr<const PclCloud> points) {
  auto out = std::make_shared<Cloud>();
  out->header = in.header;
  out->points = std::move(points);
  return out;
}

/** @brief Runs a PCL filter (e.g. pcl::VoxelGrid<PointT>) on a checked cloud: `configure(filter)`
 *  sets its parameters; the result keeps the input's header. The input is shared, not copied. */
template <class Filter, class Configure>
std::shared_ptr<Cloud> filterCloud(const Cloud& in, Configure configure) {
  requirePoints(in);
  Filter filter;
  filter.setInputCloud(in.points);
  configure(filter);
  auto points = std::make_shared<PclCloud>();
  filter.filter(*points);
  return cloudResult(in, std::move(points));
}

}  // namespace apex_nodes
