#include "apex_nodes/ros_convert.hpp"

#include <cv_bridge/cv_bridge.h>
#include <pcl_conversions/pcl_conversions.h>

namespace apex_nodes {

std::shared_ptr<const Image> fromRos(const sensor_msgs::ImageConstPtr& msg) {
  cv_bridge::CvImageConstPtr shared;
  try {
    shared = cv_bridge::toCvShare(msg);
  } catch (const cv_bridge::Exception& e) {
    throw std::invalid_argument("cannot read image with encoding '" + msg->encoding + "': " + e.what());
  }
  auto image = std::make_shared<Image>();
  image->header = msg->header;
  image->encoding = msg->encoding;
  image->mat = shared->image;
  image->owner = std::shared_ptr<const void>(shared.get(), [shared](const void*) {});  // holds the boost pointer
  return image;
}

sensor_msgs::ImagePtr toRos(const Image& image) {
  return cv_bridge::CvImage(image.header, image.encoding, image.mat).toImageMsg();
}

std::shared_ptr<const Cloud> fromRos(const sensor_msgs::PointCloud2ConstPtr& msg) {
  bool x = false, y = false, z = false;
  for (const auto& f : msg->fields) x |= f.name == "x", y |= f.name == "y", z |= f.name == "z";
  if (!(x && y && z)) throw std::invalid_argument("point cloud on frame '" + msg->header.frame_id + "' has no x, y, z fields");
  auto points = std::make_shared<PclCloud>();
  pcl::fromROSMsg(*msg, *points);
  auto cloud = std::make_shared<Cloud>();
  cloud->header = msg->header;
  cloud->points = std::move(points);
  return cloud;
}

sensor_msgs::PointCloud2Ptr toRos(const Cloud& cloud) {
  auto msg = boost::make_shared<sensor_msgs::PointCloud2>();
  pcl::toROSMsg(*cloud.points, *msg);
  msg->header = cloud.header;
  return msg;
}

}  // namespace apex_nodes
