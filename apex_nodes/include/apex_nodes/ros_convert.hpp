// Images and clouds to and from ROS messages: only at the graph's edges.
#pragma once

#include <sensor_msgs/Image.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

#include "apex_nodes/ros_cloud.hpp"
#include "apex_nodes/types.hpp"

namespace apex_nodes {

/** @brief Shares the message's pixels (no copy): the Image keeps the message alive.
 *  Throws std::invalid_argument naming what is wrong for a message whose sizes, step or
 *  encoding do not add up (checked in 64 bits before any pixel is read). */
std::shared_ptr<const Image> fromRos(const sensor_msgs::ImageConstPtr& msg);
/** @brief A ROS message of the image (its own copy of the pixels, as ROS needs). */
sensor_msgs::ImagePtr toRos(const Image& image);
/** @brief A cloud received as itself (ros_cloud.hpp), shared, once checkCloud (cloud.hpp) finds
 *  its layout sound; else throws std::invalid_argument naming the flaw. */
std::shared_ptr<const Cloud> fromRos(const boost::shared_ptr<const Cloud>& msg);
/** @brief A sensor_msgs/PointCloud2 as a cloud (a copy of its points, every field), checked. */
std::shared_ptr<const Cloud> fromRos(const sensor_msgs::PointCloud2ConstPtr& msg);
/** @brief The cloud as a message to publish: its points shared, not copied. */
boost::shared_ptr<Cloud> toRos(const Cloud& cloud);
/** @brief A scan's valid ranges as points in its plane (z = 0), with their intensity (x, y, z,
 *  intensity) when the scan has intensities. Throws std::invalid_argument for mismatched
 *  arrays, non-finite angles, or a scan with no range inside its limits. */
std::shared_ptr<const Cloud> scanToCloud(const sensor_msgs::LaserScan& scan);

}  // namespace apex_nodes
