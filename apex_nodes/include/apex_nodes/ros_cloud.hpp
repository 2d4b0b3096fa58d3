// A Cloud (types.hpp) is a ROS message: sensor_msgs/PointCloud2 on the wire (same name, MD5 and
// definition), read straight into the cloud's points and written from them. So a subscriber
// gets every field without a conversion, a publisher in the same process (nodelets) passes the
// cloud by pointer, and the header stays exact (pcl::PCLPointCloud2's own header keeps only
// microseconds, pcl_conversions' message for it would lose the stamp's nanoseconds).
#pragma once

#include <ros/serialization.h>
#include <sensor_msgs/PointCloud2.h>

#include <cstdint>
#include <memory>

#include "apex_nodes/types.hpp"

namespace ros {
namespace message_traits {

template <>
struct MD5Sum<apex_nodes::Cloud> {
  static const char* value() { return MD5Sum<sensor_msgs::PointCloud2>::value(); }
  static const char* value(const apex_nodes::Cloud&) { return value(); }
};
template <>
struct DataType<apex_nodes::Cloud> {
  static const char* value() { return DataType<sensor_msgs::PointCloud2>::value(); }
  static const char* value(const apex_nodes::Cloud&) { return value(); }
};
template <>
struct Definition<apex_nodes::Cloud> {
  static const char* value() { return Definition<sensor_msgs::PointCloud2>::value(); }
  static const char* value(const apex_nodes::Cloud&) { return value(); }
};
template <>
struct HasHeader<apex_nodes::Cloud> : TrueType {};

}  // namespace message_traits

namespace serialization {

/** The fields in sensor_msgs/PointCloud2's order; PCL's integer types are copied through the
 *  message's uint32 (pcl::uindex_t may be built wider). */
template <>
struct Serializer<apex_nodes::Cloud> {
  template <typename Stream>
  static void write(Stream& stream, const apex_nodes::Cloud& m) {
    static const pcl::PCLPointCloud2 kNone;
    const pcl::PCLPointCloud2& p = m.points ? *m.points : kNone;
    stream.next(m.header);
    stream.next(std::uint32_t(p.height));
    stream.next(std::uint32_t(p.width));
    stream.next(std::uint32_t(p.fields.size()));
    for (const auto& f : p.fields) {
      stream.next(f.name);
      stream.next(std::uint32_t(f.offset));
      stream.next(std::uint8_t(f.datatype));
      stream.next(std::uint32_t(f.count));
    }
    stream.next(std::uint8_t(p.is_bigendian));
    stream.next(std::uint32_t(p.point_step));
    stream.next(std::uint32_t(p.row_step));
    stream.next(p.data);
    stream.next(std::uint8_t(p.is_dense));
  }

  template <typename Stream>
  static void read(Stream& stream, apex_nodes::Cloud& m) {
    auto p = std::make_shared<pcl::PCLPointCloud2>();
    stream.next(m.header);
    p->height = next<std::uint32_t>(stream);
    p->width = next<std::uint32_t>(stream);
    p->fields.resize(next<std::uint32_t>(stream));
    for (auto& f : p->fields) {
      stream.next(f.name);
      f.offset = next<std::uint32_t>(stream);
      f.datatype = next<std::uint8_t>(stream);
      f.count = next<std::uint32_t>(stream);
    }
    p->is_bigendian = next<std::uint8_t>(stream);
    p->point_step = next<std::uint32_t>(stream);
    p->row_step = next<std::uint32_t>(stream);
    stream.next(p->data);
    p->is_dense = next<std::uint8_t>(stream);
    p->header.frame_id = m.header.frame_id;
    m.points = std::move(p);
  }

  static std::uint32_t serializedLength(const apex_nodes::Cloud& m) {
    std::uint32_t n = serializationLength(m.header) + 4 + 4 + 4 + 1 + 4 + 4 + 1;  // sizes, endianness, steps, dense
    if (!m.points) return n + 4;
    for (const auto& f : m.points->fields) n += serializationLength(f.name) + 4 + 1 + 4;
    return n + serializationLength(m.points->data);
  }

 private:
  template <class T, typename Stream>
  static T next(Stream& stream) {
    T v{};
    stream.next(v);
    return v;
  }
};

}  // namespace serialization
}  // namespace ros
