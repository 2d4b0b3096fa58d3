#include "apex_nodes/ros_convert.hpp"

#include <cv_bridge/cv_bridge.h>
#include <pcl_conversions/pcl_conversions.h>
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

/** Bytes of one value of a sensor_msgs/PointField datatype; 0 if unknown. */
Size fieldSize(std::uint8_t datatype) {
  using F = sensor_msgs::PointField;
  switch (datatype) {
    case F::INT8: case F::UINT8: return 1;
    case F::INT16: case F::UINT16: return 2;
    case F::INT32: case F::UINT32: case F::FLOAT32: return 4;
    case F::FLOAT64: return 8;
    default: return 0;
  }
}

void checkCloud(const sensor_msgs::PointCloud2& m) {
  auto bad = [&](const std::string& why) {
    throw std::invalid_argument("point cloud " + std::to_string(m.width) + "x" + std::to_string(m.height) + " on frame '" +
                                m.header.frame_id + "': " + why);
  };
  if (Size(m.width) * Size(m.height) > (Size(1) << 28)) bad("absurd size: over 2^28 points");
  if (m.point_step == 0) bad("point_step is 0");
  bool x = false, y = false, z = false;
  for (const auto& f : m.fields) {
    const Size size = fieldSize(f.datatype);
    if (size == 0) bad("field '" + f.name + "' has the unknown datatype " + std::to_string(f.datatype));
    if (Size(f.offset) + size * std::max<Size>(1, f.count) > Size(m.point_step))
      bad("field '" + f.name + "' (offset " + std::to_string(f.offset) + ") does not fit in point_step " +
          std::to_string(m.point_step));
    x |= f.name == "x", y |= f.name == "y", z |= f.name == "z";
  }
  if (!(x && y && z)) bad("it has no x, y, z fields");
  if (Size(m.row_step) < Size(m.width) * Size(m.point_step))
    bad("row_step " + std::to_string(m.row_step) + " is shorter than width x point_step");
  if (Size(m.row_step) * Size(m.height) > Size(m.data.size()))
    bad("data has " + std::to_string(m.data.size()) + " bytes, row_step x height needs " +
        std::to_string(Size(m.row_step) * Size(m.height)));
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

std::shared_ptr<const Cloud> fromRos(const sensor_msgs::PointCloud2ConstPtr& msg) {
  checkCloud(*msg);
  auto points = std::make_shared<PclCloud>();
  if (msg->width != 0 && msg->height != 0) pcl::fromROSMsg(*msg, *points);  // PCL indexes point 0 of an empty cloud
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

std::shared_ptr<const Cloud> scanToCloud(const sensor_msgs::LaserScan& scan) {
  if (!scan.intensities.empty() && scan.intensities.size() != scan.ranges.size())
    throw std::invalid_argument("scan on frame '" + scan.header.frame_id + "' has " + std::to_string(scan.ranges.size()) +
                                " ranges but " + std::to_string(scan.intensities.size()) + " intensities");
  if (!std::isfinite(scan.angle_min) || !std::isfinite(scan.angle_increment))
    throw std::invalid_argument("scan on frame '" + scan.header.frame_id + "' has a non-finite angle_min or angle_increment");
  auto points = std::make_shared<PclCloud>();
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const float r = scan.ranges[i];
    if (!std::isfinite(r) || r < scan.range_min || r > scan.range_max) continue;
    const double a = scan.angle_min + i * static_cast<double>(scan.angle_increment);
    points->push_back(PointT(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), 0.f));
  }
  if (points->empty())
    throw std::invalid_argument("scan of " + std::to_string(scan.ranges.size()) + " ranges has none within [" +
                                std::to_string(scan.range_min) + ", " + std::to_string(scan.range_max) + "]");
  auto out = std::make_shared<Cloud>();
  out->header = scan.header;
  out->points = std::move(points);
  return out;
}

}  // namespace apex_nodes
