// libFuzzer: a message from the network -> what a node receives. The first byte picks an
// Image, a PointCloud2 or a LaserScan; message_bytes.hpp says how the rest sets its fields.
// A message the conversion refuses (std::invalid_argument, naming what is wrong) is fine;
// one it accepts is read to the last pixel or point, so sizes that do not add up show as
// an AddressSanitizer report.
#include <boost/make_shared.hpp>

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "apex_nodes/cloud.hpp"
#include "apex_nodes/ros_convert.hpp"
#include "message_bytes.hpp"

namespace {

void touch(const apex_nodes::Image& image) {
  volatile unsigned sum = 0;
  const cv::Mat& m = image.mat;
  for (int r = 0; r < m.rows; ++r) {
    const std::uint8_t* row = m.ptr<std::uint8_t>(r);
    for (std::size_t b = 0; b < m.cols * m.elemSize(); ++b) sum = sum + row[b];
  }
}

/** What a cloud node does with it: the x, y, z view, every point selected whole. */
void touch(const apex_nodes::Cloud& cloud) {
  volatile float sum = 0;
  const auto xyz = apex_nodes::xyzOf(cloud);
  for (const auto& p : *xyz) sum = sum + p.x + p.y + p.z;
  pcl::Indices all(xyz->size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<pcl::index_t>(i);
  sum = sum + static_cast<float>(apex_nodes::selectPoints(*cloud.points, all)->data.size());
}

/** The message's bytes read as a subscriber reads them (ros_cloud.hpp), then checked. */
std::shared_ptr<const apex_nodes::Cloud> received(const sensor_msgs::PointCloud2& m) {
  std::vector<std::uint8_t> bytes(ros::serialization::serializationLength(m));
  ros::serialization::OStream out(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::serialize(out, m);
  auto cloud = boost::make_shared<apex_nodes::Cloud>();
  ros::serialization::IStream in(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::deserialize(in, *cloud);
  return apex_nodes::fromRos(boost::shared_ptr<const apex_nodes::Cloud>(cloud));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  apex_fuzz::Reader in(data, size);
  try {
    switch (in.take<std::uint8_t>() % 3) {
      case apex_fuzz::kImage:
        touch(*apex_nodes::fromRos(boost::make_shared<const sensor_msgs::Image>(apex_fuzz::readImage(in))));
        break;
      case apex_fuzz::kCloud: {
        const auto m = boost::make_shared<const sensor_msgs::PointCloud2>(apex_fuzz::readCloud(in));
        touch(*apex_nodes::fromRos(m));
        touch(*received(*m));
      } break;
      case apex_fuzz::kScan:
        touch(*apex_nodes::scanToCloud(apex_fuzz::readScan(in)));
        break;
    }
  } catch (const std::invalid_argument&) {  // refused, naming what is wrong: what a node reports
  }
  return 0;
}
