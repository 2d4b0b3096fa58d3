// The byte layout fuzz_ros_messages reads a message from, and fuzz_make_seeds writes: every
// field a node's conversion looks at, each as the fuzzer may set it, and the payload as the
// rest. (Not ROS's own serialisation: its deserialiser allocates what a length prefix says
// before checking the bytes are there, which is roscpp's matter, not ours.)
#pragma once

#include <sensor_msgs/Image.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace apex_fuzz {

/** Reads values in order; past the end, everything is zero. */
class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  template <class T>
  T take() {
    T v{};
    const std::size_t n = std::min(sizeof(T), size_ - pos_);
    std::memcpy(&v, data_ + pos_, n);
    pos_ += n;
    return v;
  }
  std::string text() {
    const std::size_t n = std::min<std::size_t>(take<std::uint8_t>(), size_ - pos_);
    std::string s(reinterpret_cast<const char*>(data_ + pos_), n);
    pos_ += n;
    return s;
  }
  std::vector<std::uint8_t> rest() {
    std::vector<std::uint8_t> r(data_ + pos_, data_ + size_);
    pos_ = size_;
    return r;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_, pos_ = 0;
};

class Writer {
 public:
  template <class T>
  void put(T v) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  void text(const std::string& s) {
    put<std::uint8_t>(static_cast<std::uint8_t>(s.size()));
    bytes.insert(bytes.end(), s.begin(), s.end());
  }
  std::vector<std::uint8_t> bytes;
};

enum Kind : std::uint8_t { kImage = 0, kCloud = 1, kScan = 2 };

inline sensor_msgs::Image readImage(Reader& r) {
  sensor_msgs::Image m;
  m.header.frame_id = "camera";
  m.width = r.take<std::uint32_t>(), m.height = r.take<std::uint32_t>(), m.step = r.take<std::uint32_t>();
  m.is_bigendian = r.take<std::uint8_t>();
  m.encoding = r.text();
  m.data = r.rest();
  return m;
}

inline void writeImage(Writer& w, const sensor_msgs::Image& m) {
  w.put<std::uint8_t>(kImage);
  w.put(m.width), w.put(m.height), w.put(m.step), w.put<std::uint8_t>(m.is_bigendian);
  w.text(m.encoding);
  w.bytes.insert(w.bytes.end(), m.data.begin(), m.data.end());
}

inline sensor_msgs::PointCloud2 readCloud(Reader& r) {
  sensor_msgs::PointCloud2 m;
  m.header.frame_id = "lidar";
  m.width = r.take<std::uint32_t>(), m.height = r.take<std::uint32_t>();
  m.point_step = r.take<std::uint32_t>(), m.row_step = r.take<std::uint32_t>();
  m.is_bigendian = r.take<std::uint8_t>(), m.is_dense = r.take<std::uint8_t>();
  const int fields = r.take<std::uint8_t>() % 8;
  for (int i = 0; i < fields; ++i) {
    sensor_msgs::PointField f;
    f.name = r.text();
    f.offset = r.take<std::uint32_t>(), f.datatype = r.take<std::uint8_t>(), f.count = r.take<std::uint32_t>();
    m.fields.push_back(f);
  }
  m.data = r.rest();
  return m;
}

inline void writeCloud(Writer& w, const sensor_msgs::PointCloud2& m) {
  w.put<std::uint8_t>(kCloud);
  w.put(m.width), w.put(m.height), w.put(m.point_step), w.put(m.row_step);
  w.put<std::uint8_t>(m.is_bigendian), w.put<std::uint8_t>(m.is_dense);
  w.put<std::uint8_t>(static_cast<std::uint8_t>(m.fields.size()));
  for (const auto& f : m.fields) w.text(f.name), w.put(f.offset), w.put(f.datatype), w.put(f.count);
  w.bytes.insert(w.bytes.end(), m.data.begin(), m.data.end());
}

inline sensor_msgs::LaserScan readScan(Reader& r) {
  sensor_msgs::LaserScan m;
  m.header.frame_id = "laser";
  m.angle_min = r.take<float>(), m.angle_max = r.take<float>(), m.angle_increment = r.take<float>();
  m.range_min = r.take<float>(), m.range_max = r.take<float>();
  m.ranges.resize(r.take<std::uint16_t>());
  m.intensities.resize(r.take<std::uint16_t>());
  for (auto& v : m.ranges) v = r.take<float>();
  for (auto& v : m.intensities) v = r.take<float>();
  return m;
}

inline void writeScan(Writer& w, const sensor_msgs::LaserScan& m) {
  w.put<std::uint8_t>(kScan);
  w.put(m.angle_min), w.put(m.angle_max), w.put(m.angle_increment), w.put(m.range_min), w.put(m.range_max);
  w.put(static_cast<std::uint16_t>(m.ranges.size())), w.put(static_cast<std::uint16_t>(m.intensities.size()));
  for (float v : m.ranges) w.put(v);
  for (float v : m.intensities) w.put(v);
}

}  // namespace apex_fuzz
