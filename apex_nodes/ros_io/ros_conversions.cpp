// The conversions of ROS message types to the library's port types (ros_message.hpp): one table,
// for TopicSubscriber and BagReader. A message is checked before it is deserialized: its MD5 must
// be this build's (the same definition), and its bytes a whole message (message_fields.hpp), so a
// truncated message or a count past its end is an error, never a read out of bounds.
#include <std_msgs/Bool.h>
#include <std_msgs/Float32.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Int32.h>
#include <std_msgs/Int64.h>
#include <std_msgs/String.h>

#include <boost/make_shared.hpp>

#include <limits>
#include <map>

#include "apex_nodes/ros_convert.hpp"
#include "apex_nodes/ros_message.hpp"
#include "apex_nodes/ros_results.hpp"
#include "apex_nodes/stamp.hpp"  // the names of the pose and transform types
#include "message_fields.hpp"

namespace apex_nodes {
namespace {

/** The message as RosMsg, once its MD5 and bytes are sound. */
template <class RosMsg>
boost::shared_ptr<RosMsg> deserialize(const RosMessage& m) {
  namespace mt = ros::message_traits;
  static const MessageSchema schema(mt::datatype<RosMsg>(), mt::definition<RosMsg>());  // this build's
  if (m.md5sum != mt::md5sum<RosMsg>())
    throw std::invalid_argument(m.datatype + " message of MD5 " + m.md5sum + " has another definition than this build's (MD5 " +
                                mt::md5sum<RosMsg>() + ")");
  schema.check(m.bytes.data(), m.bytes.size());
  auto out = boost::make_shared<RosMsg>();
  ros::serialization::IStream stream(const_cast<std::uint8_t*>(m.bytes.data()), static_cast<std::uint32_t>(m.bytes.size()));
  ros::serialization::deserialize(stream, *out);
  return out;
}

/** A ROS message shared as the port's payload (no copy: the pointer keeps it). */
template <class T>
apex::Message shared(const boost::shared_ptr<T>& p) {
  return apex::Message::share<T>(std::shared_ptr<const T>(p.get(), [p](const T*) {}));
}

int toInt(std::int64_t v) {
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    throw std::invalid_argument("std_msgs/Int64 " + std::to_string(v) + " does not fit an int");
  return static_cast<int>(v);
}

using Table = std::map<std::string, RosConversion>;

/** Messages of RosMsg's datatype on ports of T, converted by `convert` (of a boost::shared_ptr<RosMsg>). */
template <class T, class RosMsg, class Convert>
void add(Table& table, Convert convert) {
  table[ros::message_traits::datatype<RosMsg>()] =
      RosConversion{apex::typeOf<T>(), [convert](const RosMessage& m) { return convert(deserialize<RosMsg>(m)); }};
}

/** Types that travel as the ROS message itself. */
template <class RosMsg>
void addItself(Table& table) {
  add<RosMsg, RosMsg>(table, [](const boost::shared_ptr<RosMsg>& p) { return shared(p); });
}

/** A std_msgs number or text as T: its `data`. */
template <class T, class RosMsg>
void addData(Table& table) {
  add<T, RosMsg>(table, [](const boost::shared_ptr<RosMsg>& p) { return apex::Message::make<T>(T(p->data)); });
}

const Table& table() {
  static const Table t = [] {
    Table t;
    add<Image, sensor_msgs::Image>(
        t, [](const sensor_msgs::ImagePtr& p) { return apex::Message::share<Image>(fromRos(sensor_msgs::ImageConstPtr(p))); });
    add<Cloud, Cloud>(t, [](const boost::shared_ptr<Cloud>& p) {  // read straight into the cloud (ros_cloud.hpp)
      return apex::Message::share<Cloud>(fromRos(boost::shared_ptr<const Cloud>(p)));
    });
    addItself<sensor_msgs::LaserScan>(t);
    addItself<sensor_msgs::CameraInfo>(t);
    addItself<geometry_msgs::PoseStamped>(t);
    addItself<geometry_msgs::PoseArray>(t);
    addItself<geometry_msgs::TransformStamped>(t);
    addData<double, std_msgs::Float64>(t);
    addData<double, std_msgs::Float32>(t);
    addData<int, std_msgs::Int32>(t);
    add<int, std_msgs::Int64>(t, [](const std_msgs::Int64Ptr& p) { return apex::Message::make<int>(toInt(p->data)); });
    addData<bool, std_msgs::Bool>(t);
    addData<std::string, std_msgs::String>(t);
    add<Regions, apex::Regions>(t, [](const apex::RegionsPtr& p) { return apex::Message::make<Regions>(fromRos(*p)); });
    return t;
  }();
  return t;
}

}  // namespace

const RosConversion* findConversion(const std::string& datatype) {
  auto it = table().find(datatype);
  return it == table().end() ? nullptr : &it->second;
}

std::vector<std::string> convertedDatatypes() {
  std::vector<std::string> out;
  for (const auto& [datatype, conversion] : table()) out.push_back(datatype);
  return out;
}

const apex::TypeInfo* portType(const std::string& datatype) {
  const RosConversion* c = findConversion(datatype);
  return c ? c->type : apex::typeOf<RosMessage>();
}

apex::Message toPort(std::shared_ptr<const RosMessage> message) {
  const RosConversion* c = findConversion(message->datatype);
  return c ? c->convert(*message) : apex::Message::share<RosMessage>(std::move(message));
}

}  // namespace apex_nodes
