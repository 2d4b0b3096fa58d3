// RosMessage's header, and its inspector: recorded (BagWriter) as the message it is.
#include "apex_nodes/ros_message.hpp"

#include <std_msgs/String.h>

#include <boost/shared_ptr.hpp>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>

#include "apex/ros/inspect.hpp"
#include "message_fields.hpp"

namespace apex_nodes {

std::optional<std_msgs::Header> RosMessage::header() const {
  if (!startsWithHeader(definition)) return std::nullopt;
  ByteCursor c(bytes.data(), bytes.size());
  std_msgs::Header h;
  try {
    h.seq = c.next<std::uint32_t>();
    h.stamp.sec = c.next<std::uint32_t>();
    h.stamp.nsec = c.next<std::uint32_t>();
    h.frame_id = c.text();
  } catch (const TruncatedMessage&) {
    return std::nullopt;
  }
  return h;
}

ros::Time RosMessage::stamp() const {
  const auto h = header();
  return h ? h->stamp : ros::Time();
}

bool RosMessage::setStamp(const ros::Time& stamp) {
  if (!header()) return false;
  const std::uint32_t fields[2] = {stamp.sec, stamp.nsec};  // after the seq, little-endian as ROS's wire
  std::memcpy(bytes.data() + sizeof(std::uint32_t), fields, sizeof fields);
  return true;
}

namespace {

/** "nav_msgs/Odometry, 692 bytes, frame 'odom' at 1700000000.500000000". */
std::string describe(const RosMessage& m) {
  std::string out = m.datatype + ", " + std::to_string(m.bytes.size()) + " bytes";
  if (const auto h = m.header()) {
    char stamp[32];
    std::snprintf(stamp, sizeof stamp, "%u.%09u", h->stamp.sec, h->stamp.nsec);
    out += ", frame '" + h->frame_id + "' at " + stamp;
  }
  return out;
}

/** Published (~inspect, previews) and recorded (serialize) as itself: each topic is advertised as the
 *  type of its first message; a later message of another type is not published there (ROS cannot
 *  change a topic's type), while BagWriter, which records by message, records it. */
apex::Inspector inspector() {
  apex::Inspector i;
  auto advertised = std::make_shared<std::pair<std::mutex, std::map<std::string, std::string>>>();  // topic → MD5
  i.message_type = "*";
  i.advertise = [](ros::NodeHandle&, const std::string&, const ros::SubscriberStatusCallback&) {
    return ros::Publisher();  // (advertise_as instead)
  };
  i.advertise_as = [advertised](ros::NodeHandle& nh, const std::string& topic, const apex::Message& first,
                                const ros::SubscriberStatusCallback& connected) {
    auto p = first.as<RosMessage>();
    if (!p) return ros::Publisher();
    ros::AdvertiseOptions options(topic, 1, p->md5sum, p->datatype, p->definition, connected);
    ros::Publisher pub = nh.advertise(options);
    std::lock_guard<std::mutex> lock(advertised->first);
    if (pub) advertised->second[pub.getTopic()] = p->md5sum;
    return pub;
  };
  i.publish = [advertised](const ros::Publisher& pub, const apex::Message& m) {
    auto p = m.as<RosMessage>();
    if (!p) return;
    {
      std::lock_guard<std::mutex> lock(advertised->first);
      auto it = advertised->second.find(pub.getTopic());
      if (it == advertised->second.end() || it->second != p->md5sum) return;  // another type than the topic's
    }
    pub.publish(boost::shared_ptr<const RosMessage>(p.get(), [p](const RosMessage*) {}));  // shared in-process
  };
  i.serialize = [](const apex::Message& m) {
    apex::SerializedMessage out;
    if (auto p = m.as<RosMessage>()) out = {p->datatype, p->md5sum, p->definition, p->bytes, p->stamp()};
    return out;
  };
  i.describe = [](const apex::Message& m) {
    auto p = m.as<RosMessage>();
    return p ? describe(*p) : std::string();
  };
  return i;
}

const bool kRegistered = apex::registerInspector(apex::typeOf<RosMessage>(), inspector());

}  // namespace
}  // namespace apex_nodes
