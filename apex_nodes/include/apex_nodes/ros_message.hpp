// A ROS message of any type, as TopicSubscriber and BagReader receive one whose type the library
// has no port type for (nav_msgs/Odometry, sensor_msgs/Imu, a lab's own messages): its type's
// name, MD5 and full definition, and its serialized bytes. It is itself a ROS message of any type,
// as topic_tools::ShapeShifter is (the traits below): a subscriber or a bag reads its bytes into
// it with one copy, and ros::Publisher and rosbag write it as the type it holds. (ShapeShifter
// keeps its bytes private: reading them would copy them again for every field read.)
//
// The conversions of ROS types to the library's typed ports (sensor_msgs/Image → Image, ...) are
// here too: one table (ros_io/ros_conversions.cpp), for TopicSubscriber and BagReader alike.
#pragma once

#include <ros/message_traits.h>
#include <ros/serialization.h>
#include <std_msgs/Header.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apex/core/message.hpp"

namespace apex_nodes {

/** @brief A ROS message of any type: shared and immutable in a graph, as every message is. */
struct RosMessage {
  std::string datatype;  ///< e.g. "nav_msgs/Odometry"
  std::string md5sum;
  std::string definition;  ///< the full text, with a `MSG: pkg/Type` section per type it uses
  std::vector<std::uint8_t> bytes;  ///< ROS's serialization (without the length in front)

  /** @brief Its std_msgs/Header when the type's first field is `Header header` (its bytes then
   *  start with it); none for another type, or bytes too short to hold it. */
  std::optional<std_msgs::Header> header() const;
  /** @brief header()'s stamp; zero without a header. */
  ros::Time stamp() const;
  /** @brief Sets header()'s stamp in its bytes; false (nothing changed) without a header. */
  bool setStamp(const ros::Time& stamp);
  bool operator==(const RosMessage& other) const {
    return datatype == other.datatype && md5sum == other.md5sum && definition == other.definition && bytes == other.bytes;
  }
};

/** @brief A typed ROS message serialized into a RosMessage (tests, and types made in C++). */
template <class M>
RosMessage toRosMessage(const M& message) {
  namespace mt = ros::message_traits;
  RosMessage out{mt::datatype<M>(), mt::md5sum<M>(), mt::definition<M>(), {}};
  out.bytes.resize(ros::serialization::serializationLength(message));
  ros::serialization::OStream stream(out.bytes.data(), static_cast<std::uint32_t>(out.bytes.size()));
  ros::serialization::serialize(stream, message);
  return out;
}

/** @brief How messages of one ROS type become a typed port's. */
struct RosConversion {
  const apex::TypeInfo* type;  ///< the port's type, e.g. apex_nodes/Image for sensor_msgs/Image
  /** Throws std::invalid_argument for a message of another MD5 (another definition of the type),
   *  bytes that do not hold a whole message, or content the port type refuses (an image whose
   *  sizes do not add up). */
  std::function<apex::Message(const RosMessage&)> convert;
};

/** @brief The conversion of `datatype` ("sensor_msgs/Image"), or nullptr: sensor_msgs/Image,
 *  PointCloud2, LaserScan, CameraInfo; geometry_msgs/PoseStamped, PoseArray, TransformStamped;
 *  std_msgs/Float64 and Float32 (double), Int32 and Int64 (int), Bool, String; apex/Regions. */
const RosConversion* findConversion(const std::string& datatype);
/** @brief The datatypes findConversion knows, sorted: for descriptions. */
std::vector<std::string> convertedDatatypes();
/** @brief The port type of messages of `datatype`: its conversion's, else RosMessage. */
const apex::TypeInfo* portType(const std::string& datatype);
/** @brief A received message on its port: converted when its type has a conversion, else itself
 *  (shared, not copied). */
apex::Message toPort(std::shared_ptr<const RosMessage> message);

}  // namespace apex_nodes

APEX_TYPE_NAME(apex_nodes::RosMessage, "ROS message");

// A RosMessage is a ROS message of any type: statically "*", each instance its own.
namespace ros {
namespace message_traits {

template <>
struct IsMessage<apex_nodes::RosMessage> : TrueType {};
template <>
struct IsMessage<const apex_nodes::RosMessage> : TrueType {};
template <>
struct MD5Sum<apex_nodes::RosMessage> {
  static const char* value(const apex_nodes::RosMessage& m) { return m.md5sum.c_str(); }
  static const char* value() { return "*"; }
};
template <>
struct DataType<apex_nodes::RosMessage> {
  static const char* value(const apex_nodes::RosMessage& m) { return m.datatype.c_str(); }
  static const char* value() { return "*"; }
};
template <>
struct Definition<apex_nodes::RosMessage> {
  static const char* value(const apex_nodes::RosMessage& m) { return m.definition.c_str(); }
};

}  // namespace message_traits

namespace serialization {

template <>
struct Serializer<apex_nodes::RosMessage> {
  template <typename Stream>
  static void write(Stream& stream, const apex_nodes::RosMessage& m) {
    if (!m.bytes.empty()) std::memcpy(stream.advance(static_cast<std::uint32_t>(m.bytes.size())), m.bytes.data(), m.bytes.size());
  }
  /** The whole rest of the stream: a message is read alone, after its length. */
  template <typename Stream>
  static void read(Stream& stream, apex_nodes::RosMessage& m) {
    const std::uint32_t n = stream.getLength();
    m.bytes.assign(stream.getData(), stream.getData() + n);
    stream.advance(n);
  }
  static std::uint32_t serializedLength(const apex_nodes::RosMessage& m) { return static_cast<std::uint32_t>(m.bytes.size()); }
};

/** The type as the connection (a publisher's, a bag's) says. */
template <>
struct PreDeserialize<apex_nodes::RosMessage> {
  static void notify(const PreDeserializeParams<apex_nodes::RosMessage>& params) {
    if (!params.connection_header) return;
    const auto& h = *params.connection_header;
    auto get = [&h](const char* key) {
      auto it = h.find(key);
      return it == h.end() ? std::string() : it->second;
    };
    params.message->datatype = get("type");
    params.message->md5sum = get("md5sum");
    params.message->definition = get("message_definition");
  }
};

}  // namespace serialization
}  // namespace ros
