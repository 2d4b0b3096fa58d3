// What flows between APEX's perception nodes. Each keeps the ROS header (stamp,
// frame_id) with its payload, so results match sensor time and tf2 can
// transform them. Messages are shared and immutable: a node never changes an
// input, it publishes a new object.
#pragma once

#include <pcl/PCLPointCloud2.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/LaserScan.h>
#include <std_msgs/Header.h>

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "apex/core/message.hpp"

namespace apex_nodes {

/** @brief An image: pixels, their encoding (sensor_msgs/image_encodings names, e.g. "bgr8",
 *  "mono8") and the header of the frame it came from. `owner` keeps borrowed pixels
 *  alive (e.g. the ROS message a subscriber shares without copying). */
struct Image {
  std_msgs::Header header;
  std::string encoding;
  cv::Mat mat;
  std::shared_ptr<const void> owner;
};

/** @brief A point cloud as its sensor sent it: every field of every point (x, y, z and rgb,
 *  intensity, ring, time, normals...) in PCL's field-described layout, shared, never copied to be
 *  passed on; and the header of its sensor message (exact: `points->header` is not used).
 *  cloud.hpp has what nodes do with it; ros_cloud.hpp makes it a ROS message. */
struct Cloud {
  std_msgs::Header header;
  std::shared_ptr<const pcl::PCLPointCloud2> points;
};

/** @brief Clusters of one cloud (e.g. from EuclideanClustering), each with every field of its
 *  points, and the cloud's header. */
struct Clusters {
  std_msgs::Header header;
  std::vector<std::shared_ptr<const pcl::PCLPointCloud2>> clusters;
};

/** @brief One connected region of a binary image. */
struct Region {
  cv::Rect box;
  double area = 0;
  cv::Point2d centroid;
  int label = -1;  ///< a classifier's class (e.g. DigitClassifier's digit); -1: none
  double confidence = 0;  ///< the classifier's confidence in `label`, 0..1; > 0 with label -1: rejected
};

/** @brief Regions found in one image, with that image's header and size. */
struct Regions {
  std_msgs::Header header;
  cv::Size image_size;
  std::vector<Region> regions;
};

/** @brief The header as the next message in a chain should carry it. */
inline const std_msgs::Header& headerOf(const Image& i) { return i.header; }

}  // namespace apex_nodes

APEX_TYPE_NAME(apex_nodes::Image, "apex_nodes/Image");
APEX_TYPE_NAME(apex_nodes::Cloud, "apex_nodes/Cloud");
APEX_TYPE_NAME(apex_nodes::Regions, "apex_nodes/Regions");
APEX_TYPE_NAME(apex_nodes::Clusters, "apex_nodes/Clusters");
APEX_TYPE_NAME(sensor_msgs::LaserScan, "sensor_msgs/LaserScan");  // scans travel as the ROS message itself
// A camera's model (K, D, R, P, size, binning, ROI) travels as the ROS message itself, on a port of
// its own beside the image it belongs to (same header): a node that needs geometry takes both.
APEX_TYPE_NAME(sensor_msgs::CameraInfo, "sensor_msgs/CameraInfo");
