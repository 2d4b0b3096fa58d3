// A list parameter that holds a point or a direction (a viewpoint, an axis): x, y, z.
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

namespace apex_nodes {

/** @brief The parameter's three numbers; throws std::invalid_argument naming it if it has not three. */
inline Eigen::Vector3f threeNumbers(const std::vector<double>& v, const char* name) {
  if (v.size() != 3)
    throw std::invalid_argument(std::string("'") + name + "' takes three numbers (x, y, z), not " + std::to_string(v.size()));
  return Eigen::Vector3d(v[0], v[1], v[2]).cast<float>();
}

}  // namespace apex_nodes
