// ~inspect for the node library's types: images as sensor_msgs/Image, clouds
// as sensor_msgs/PointCloud2 (every field), scans, camera models and maps as themselves, the image
// library's results as this package's messages (ros_results.hpp) (see apex/ros/inspect.hpp).
// A ROS message of any type (RosMessage) has its own, in ros_message.cpp.
#include <sensor_msgs/LaserScan.h>

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>

#include "apex/ros/inspect.hpp"
#include "apex_nodes/cloud.hpp"
#include "apex_nodes/maps.hpp"
#include "apex_nodes/stamp.hpp"
#include "apex_nodes/ros_convert.hpp"
#include "apex_nodes/ros_results.hpp"

namespace apex_nodes {
namespace {

/** T's inspector: its ROS message from ros_results.hpp's toRos, described (beside a preview) as
 *  `describe` says, e.g. "12 regions". */
template <class T, class Describe>
void addResult(Describe describe) {
  using RosMsg = decltype(toRos(std::declval<const T&>()));
  apex::addInspector<T, RosMsg>([](const T& v) { return toRos(v); });
  apex::addDescribe<T>(describe);
}

/** "1 region", "12 regions". */
std::string count(std::size_t n, const std::string& one, const std::string& many = "") {
  return std::to_string(n) + " " + (n == 1 ? one : many.empty() ? one + "s" : many);
}

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
  // Maps (pcl/maps.cpp) as themselves: rviz's Map display shows the occupancy grid.
  apex::addInspector<nav_msgs::OccupancyGrid, nav_msgs::OccupancyGrid>([](const nav_msgs::OccupancyGrid& g) { return g; });
  apex::addDescribe<nav_msgs::OccupancyGrid>([](const nav_msgs::OccupancyGrid& g) {
    return std::to_string(g.info.width) + "×" + std::to_string(g.info.height) + " cells";
  });
  apex::addInspector<nav_msgs::MapMetaData, nav_msgs::MapMetaData>([](const nav_msgs::MapMetaData& m) { return m; });
  // The image library's results, as apex/Regions, apex/Contours, apex/LineSegments, apex/Circles,
  // apex/FiducialMarkers, apex/ChessboardCorners, apex/Keypoints, apex/Matches, apex/Homography, apex/Tracks.
  addResult<Regions>([](const Regions& r) { return count(r.regions.size(), "region"); });
  addResult<Contours>([](const Contours& c) { return count(c.contours.size(), "contour"); });
  addResult<Lines>([](const Lines& l) { return count(l.lines.size(), "line"); });
  addResult<Circles>([](const Circles& c) { return count(c.circles.size(), "circle"); });
  addResult<Markers>([](const Markers& m) { return count(m.ids.size(), "marker"); });
  addResult<Corners>([](const Corners& c) { return c.found ? count(c.corners.size(), "corner") : std::string("no board"); });
  addResult<Keypoints>([](const Keypoints& k) { return count(k.keypoints.size(), "keypoint"); });
  addResult<Matches>([](const Matches& m) { return count(m.matches.size(), "match", "matches"); });
  addResult<Homography>([](const Homography& h) {
    return (h.matrix.empty() ? "none, " : "") + count(static_cast<std::size_t>(std::max(0, h.inliers)), "inlier");
  });
  addResult<Tracks>([](const Tracks& t) { return count(t.status.size(), "track"); });
  return true;
}();

}  // namespace
}  // namespace apex_nodes
