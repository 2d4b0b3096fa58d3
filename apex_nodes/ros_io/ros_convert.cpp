#include "apex_nodes/ros_convert.hpp"

#include <cv_bridge/cv_bridge.h>
#include <pcl_conversions/pcl_conversions.h>

#include "apex_nodes/cloud.hpp"
#include <sensor_msgs/image_encodings.h>

#include <cmath>

namespace apex_nodes {
namespace {

// Sizes from the network are checked in 64 bits before any pixel or point is read:
// a height x step that overflows 32 bits could otherwise match a small buffer.
using Size = std::uint64_t;
constexpr Size kMaxSide = 1 << 16;  // pixels or points per row or column: far beyond any sensor

std::string imageName(const sensor_msgs::Image& m) {
  return "image " + std::to_string(m.width) + "x" + std::to_string(m.height) + " '" + m.encoding + "' on frame '" +
         m.header.frame_id + "'";
}

void checkImage(const sensor_msgs::Image& m) {
  auto bad = [&](const std::string& why) { throw std::invalid_argument(imageName(m) + ": " + why); };
  if (m.width == 0 || m.height == 0) bad("it has no pixels");
  if (m.width > kMaxSide || m.height > kMaxSide) bad("a side is over " + std::to_string(kMaxSide) + " pixels");
  Size pixel = 0;
  try {
    namespace enc = sensor_msgs::image_encodings;
    pixel = Size(enc::numChannels(m.encoding)) * Size(enc::bitDepth(m.encoding)) / 8;
  } catch (const std::exception&) {
    bad("unknown encoding");
  }
  if (Size(m.step) < Size(m.width) * pixel)
    bad("step " + std::to_string(m.step) + " is shorter than a row (" + std::to_string(Size(m.width) * pixel) + " bytes)");
  if (Size(m.step) * Size(m.height) > Size(m.data.size()))
    bad("data has " + std::to_string(m.data.size()) + " bytes, step x height needs " +
        std::to_string(Size(m.step) * Size(m.height)));
}

}  // namespace

std::shared_ptr<const Image> fromRos(const sensor_msgs::ImageConstPtr& msg) {
  checkImage(*msg);
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

std::shared_ptr<const Cloud> fromRos(const boost::shared_ptr<const Cloud>& msg) {
  checkCloud(*msg);
  return std::shared_ptr<const Cloud>(msg.get(), [msg](const Cloud*) {});  // holds the boost pointer
}

std::shared_ptr<const Cloud> fromRos(const sensor_msgs::PointCloud2ConstPtr& msg) {
  auto points = std::make_shared<pcl::PCLPointCloud2>();
  pcl_conversions::toPCL(*msg, *points);
  auto cloud = std::make_shared<Cloud>();
  cloud->header = msg->header;
  cloud->points = std::move(points);
  checkCloud(*cloud);
  return cloud;
}

boost::shared_ptr<Cloud> toRos(const Cloud& cloud) { return boost::make_shared<Cloud>(cloud); }

namespace {

template <class Point, class Make>
std::shared_ptr<const Cloud> scanPoints(const sensor_msgs::LaserScan& scan, Make make) {
  pcl::PointCloud<Point> points;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const float r = scan.ranges[i];
    if (!std::isfinite(r) || r < scan.range_min || r > scan.range_max) continue;
    const double a = scan.angle_min + i * static_cast<double>(scan.angle_increment);
    points.push_back(make(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), i));
  }
  if (points.empty())
    throw std::invalid_argument("scan of " + std::to_string(scan.ranges.size()) + " ranges has none within [" +
                                std::to_string(scan.range_min) + ", " + std::to_string(scan.range_max) + "]");
  return makeCloud(scan.header, points);
}

}  // namespace

std::shared_ptr<const Cloud> scanToCloud(const sensor_msgs::LaserScan& scan) {
  if (!scan.intensities.empty() && scan.intensities.size() != scan.ranges.size())
    throw std::invalid_argument("scan on frame '" + scan.header.frame_id + "' has " + std::to_string(scan.ranges.size()) +
                                " ranges but " + std::to_string(scan.intensities.size()) + " intensities");
  if (!std::isfinite(scan.angle_min) || !std::isfinite(scan.angle_increment))
    throw std::invalid_argument("scan on frame '" + scan.header.frame_id + "' has a non-finite angle_min or angle_increment");
  if (scan.intensities.empty())
    return scanPoints<pcl::PointXYZ>(scan, [](float x, float y, std::size_t) { return pcl::PointXYZ(x, y, 0.f); });
  return scanPoints<pcl::PointXYZI>(
      scan, [&](float x, float y, std::size_t i) { return pcl::PointXYZI(x, y, 0.f, scan.intensities[i]); });
}

}  // namespace apex_nodes
