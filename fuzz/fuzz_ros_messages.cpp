// libFuzzer: a message from the network -> what a node receives. The first byte picks an
// Image, a PointCloud2 or a LaserScan; message_bytes.hpp says how the rest sets its fields.
// A message the conversion refuses (std::invalid_argument, naming what is wrong) is fine;
// one it accepts is read to the last pixel or point, so sizes that do not add up show as
// an AddressSanitizer report.
#include <boost/make_shared.hpp>

#include <cstddef>
#include <cstdint>
#include <stdexcept>

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

void touch(const apex_nodes::Cloud& cloud) {
  volatile float sum = 0;
  for (const auto& p : *cloud.points) sum = sum + p.x + p.y + p.z;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  apex_fuzz::Reader in(data, size);
  try {
    switch (in.take<std::uint8_t>() % 3) {
      case apex_fuzz::kImage:
        touch(*apex_nodes::fromRos(boost::make_shared<const sensor_msgs::Image>(apex_fuzz::readImage(in))));
        break;
      case apex_fuzz::kCloud:
        touch(*apex_nodes::fromRos(boost::make_shared<const sensor_msgs::PointCloud2>(apex_fuzz::readCloud(in))));
        break;
      case apex_fuzz::kScan:
        touch(*apex_nodes::scanToCloud(apex_fuzz::readScan(in)));
        break;
    }
  } catch (const std::invalid_argument&) {  // refused, naming what is wrong: what a node reports
  }
  return 0;
}
