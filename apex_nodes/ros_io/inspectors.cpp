// ~inspect for the node library's types: images as sensor_msgs/Image, clouds
// as sensor_msgs/PointCloud2 (every field), scans and camera models as themselves (see apex/ros/inspect.hpp).
#include <sensor_msgs/LaserScan.h>

#include <opencv2/imgproc.hpp>

#include "apex/ros/inspect.hpp"
#include "apex_nodes/cloud.hpp"
#include "apex_nodes/stamp.hpp"
#include "apex_nodes/ros_convert.hpp"

namespace apex_nodes {
namespace {

const bool kRegistered = [] {
  apex::addInspector<Image, sensor_msgs::Image>([](const Image& i) { return *toRos(i); });
  apex::addShrink<Image>([](const Image& i, int max_width) {  // a thumbnail: scaled down, never up
    if (i.mat.cols <= max_width || i.mat.empty()) return i;
    Image small = i;
    const double f = static_cast<double>(max_width) / i.mat.cols;
    cv::resize(i.mat, small.mat, cv::Size(), f, f, cv::INTER_AREA);
    small.owner = nullptr;
    return small;
  });
  apex::addDescribe<Image>([](const Image& i) {  // the size a preview no longer has
    return std::to_string(i.mat.cols) + "×" + std::to_string(i.mat.rows) + (i.encoding.empty() ? "" : " " + i.encoding);
  });
  apex::addInspector<Cloud, Cloud>([](const Cloud& c) { return c; });  // itself: a PointCloud2 (ros_cloud.hpp)
  apex::addDescribe<Cloud>([](const Cloud& c) {  // e.g. "307200 points: x, y, z, rgb"
    return std::to_string(pointCount(c)) + " points: " + (c.points ? fieldNames(*c.points) : "none");
  });
  apex::addInspector<sensor_msgs::LaserScan, sensor_msgs::LaserScan>([](const sensor_msgs::LaserScan& s) { return s; });
  apex::addInspector<sensor_msgs::CameraInfo, sensor_msgs::CameraInfo>([](const sensor_msgs::CameraInfo& c) { return c; });
  apex::addInspector<geometry_msgs::PoseStamped, geometry_msgs::PoseStamped>(
      [](const geometry_msgs::PoseStamped& p) { return p; });
  apex::addInspector<geometry_msgs::PoseArray, geometry_msgs::PoseArray>([](const geometry_msgs::PoseArray& p) { return p; });
  return true;
}();

}  // namespace
}  // namespace apex_nodes
