// How a port's messages become ROS messages: published for inspection (~inspect)
// and recorded into bags (BagWriter); a converter per message type. Numbers and
// strings come built in; node libraries add theirs (images, clouds) with one line:
//   static const bool ok = apex::addInspector<cv::Mat, sensor_msgs::Image>(convert);
#pragma once

#include <ros/ros.h>

#include <cstdint>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

#include "apex/core/message.hpp"

namespace apex {

/** @brief A message as ROS sends it, with what a bag needs to store it. */
struct SerializedMessage {
  std::string datatype, md5sum, definition;
  std::vector<std::uint8_t> bytes;
  ros::Time stamp;  ///< its header's stamp; zero when its type has no header
};

struct Inspector {
  std::string message_type;  ///< e.g. "std_msgs/Int32"
  /** Advertises `topic`; `connected` is called when a subscriber connects. */
  std::function<ros::Publisher(ros::NodeHandle&, const std::string& topic, const ros::SubscriberStatusCallback& connected)>
      advertise;
  std::function<void(const ros::Publisher&, const Message&)> publish;
  /** For previews (the panel's thumbnails): a smaller message at most `max_width` wide, e.g.
   *  an image scaled down; none: previews are the messages themselves. */
  std::function<Message(const Message&, int max_width)> shrink;
  /** For recording: the ROS message serialized; none for a type with no ROS message of its own. */
  std::function<SerializedMessage(const Message&)> serialize;
  /** What a message is, in a few words (e.g. "640×480 bgr8"): sent beside its previews, as the
   *  preview itself may be shrunk; none: nothing is sent. */
  std::function<std::string(const Message&)> describe;
  /** For a type whose ROS type is the message's own (a ROS message of any type): advertises the
   *  topic as `first`'s type, at the first message; `advertise` is then not used. */
  std::function<ros::Publisher(ros::NodeHandle&, const std::string& topic, const Message& first,
                               const ros::SubscriberStatusCallback& connected)>
      advertise_as;
};

/** @brief Registers the converter for messages of `type` (the last registration wins). */
bool registerInspector(const TypeInfo* type, Inspector inspector);
/** @brief How a preview of `type` is made smaller (see Inspector::shrink); after its inspector. */
bool registerShrink(const TypeInfo* type, std::function<Message(const Message&, int max_width)> shrink);

template <class T, class Shrink>
bool addShrink(Shrink shrink) {
  return registerShrink(typeOf<T>(), [shrink](const Message& m, int max_width) {
    auto p = m.as<T>();
    return p ? Message::make<T>(shrink(*p, max_width)) : m;
  });
}
/** @brief How a message of `type` is described beside its previews (see Inspector::describe); after its inspector. */
bool registerDescribe(const TypeInfo* type, std::function<std::string(const Message&)> describe);

template <class T, class Describe>
bool addDescribe(Describe describe) {
  return registerDescribe(typeOf<T>(), [describe](const Message& m) {
    auto p = m.as<T>();
    return p ? std::string(describe(*p)) : std::string();
  });
}
/** @brief The converter for `type`; a YAML-text std_msgs/String one if none is registered. */
Inspector findInspector(const TypeInfo* type);
/** @brief The readable names of the types with a ROS message of their own (a registered converter
 *  with `serialize`: built in, and what the loaded node libraries added), sorted: for errors
 *  about a type that has none. */
std::vector<std::string> inspectedTypes();

/** @brief How many messages an inspected port's topic keeps for a subscriber that is behind: a
 *  number or a word is a series where each one counts (a plot, a script scoring every frame: with
 *  1, a burst lost some), anything larger only its newest (a viewer of images or clouds). */
template <class T>
constexpr std::uint32_t inspectQueue() {
  return std::is_arithmetic_v<T> || std::is_same_v<T, std::string> ? 1000 : 1;
}

template <class T, class RosMsg, class Convert>
bool addInspector(Convert convert) {
  return registerInspector(
      typeOf<T>(),
      Inspector{ros::message_traits::datatype<RosMsg>(),
                [](ros::NodeHandle& nh, const std::string& topic, const ros::SubscriberStatusCallback& connected) {
                  return nh.advertise<RosMsg>(topic, inspectQueue<T>(), connected);
                },
                [convert](const ros::Publisher& pub, const Message& m) {
                  if (auto p = m.as<T>()) pub.publish(convert(*p));
                },
                nullptr,
                [convert](const Message& m) {
                  namespace mt = ros::message_traits;
                  SerializedMessage out{mt::datatype<RosMsg>(), mt::md5sum<RosMsg>(), mt::definition<RosMsg>(), {}, {}};
                  auto p = m.as<T>();
                  if (!p) return out;
                  const RosMsg msg = convert(*p);
                  out.bytes.resize(ros::serialization::serializationLength(msg));
                  ros::serialization::OStream stream(out.bytes.data(), static_cast<std::uint32_t>(out.bytes.size()));
                  ros::serialization::serialize(stream, msg);
                  if (const ros::Time* stamp = mt::timeStamp(msg)) out.stamp = *stamp;
                  return out;
                },
                nullptr, nullptr});
}

}  // namespace apex
