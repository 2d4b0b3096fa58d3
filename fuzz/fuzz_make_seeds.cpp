// Writes the seed corpus of fuzz_ros_messages: valid Image, PointCloud2 and LaserScan
// messages in the layout of message_bytes.hpp.
//   fuzz_make_seeds DIR
#include <sensor_msgs/point_cloud2_iterator.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "message_bytes.hpp"

namespace {

void save(const std::string& path, const apex_fuzz::Writer& w) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(w.bytes.data()), w.bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_make_seeds DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  for (const std::string encoding : {"bgr8", "mono8", "mono16", "32FC1"}) {
    sensor_msgs::Image image;
    image.header.frame_id = "camera";
    image.encoding = encoding;
    image.width = 4, image.height = 3;
    const int pixel = encoding == "bgr8" ? 3 : encoding == "mono8" ? 1 : encoding == "mono16" ? 2 : 4;
    image.step = image.width * pixel;
    image.data.assign(image.step * image.height, 7);
    apex_fuzz::Writer w;
    apex_fuzz::writeImage(w, image);
    save(dir + "/image_" + encoding, w);
  }
  sensor_msgs::PointCloud2 cloud;
  cloud.header.frame_id = "lidar";
  sensor_msgs::PointCloud2Modifier modifier(cloud);
  modifier.setPointCloud2FieldsByString(1, "xyz");
  modifier.resize(5);
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x");
  for (int i = 0; i < 5; ++i, ++x) x[0] = float(i), x[1] = 1.f, x[2] = 2.f;
  apex_fuzz::Writer wc;
  apex_fuzz::writeCloud(wc, cloud);
  save(dir + "/cloud_xyz", wc);
  sensor_msgs::LaserScan scan;
  scan.header.frame_id = "laser";
  scan.angle_min = -1.f, scan.angle_max = 1.f, scan.angle_increment = 0.5f;
  scan.range_min = 0.1f, scan.range_max = 10.f;
  scan.ranges = {1.f, 2.f, 3.f, 4.f, 5.f};
  scan.intensities = {1.f, 1.f, 1.f, 1.f, 1.f};
  apex_fuzz::Writer ws;
  apex_fuzz::writeScan(ws, scan);
  save(dir + "/scan", ws);
  return 0;
}
