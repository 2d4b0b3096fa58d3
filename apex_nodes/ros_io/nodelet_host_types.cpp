// The message types NodeletHost's ports carry, and how each goes to a nodelet and comes back.
// Messages go through ros::Publisher as boost::shared_ptr: roscpp hands the pointer itself to a
// subscriber in this process whose callback takes the same C++ type (no serialisation). Where
// the port's type is not the ROS message, the conversion copies, as marked below.
#include <pcl_conversions/pcl_conversions.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

#include <stdexcept>

#include "apex_nodes/ros_convert.hpp"
#include "nodelet_host.hpp"

namespace apex_nodes {
namespace nodelet_host {
namespace {

template <class Msg>
ros::Publisher advertiseOf(ros::NodeHandle& nh, const std::string& topic) {
  return nh.advertise<Msg>(topic, 1);
}

/** Subscribes to the nodelet's `topic` as `Msg` (its own type: no copy), converting with `convert`. */
template <class Msg, class Convert>
ros::Subscriber subscribeOf(ros::NodeHandle& nh, const std::string& topic, std::function<void(Received)> done, Convert convert) {
  return nh.subscribe<Msg>(topic, 10, [done, convert](const boost::shared_ptr<const Msg>& msg) {
    Received r;
    r.arrived = true;
    r.stamp = msg->header.stamp;
    try {
      r.message = convert(msg);
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    done(std::move(r));
  });
}

/** A type that travels as the ROS message itself (camera info, scans): shared both ways, no copy. */
template <class Msg>
RosType itself(const std::string& name) {
  return RosType{name,
                 apex::typeOf<Msg>(),
                 advertiseOf<Msg>,
                 [](const ros::Publisher& pub, const apex::Message& m) {
                   if (auto p = m.as<Msg>()) pub.publish(boost::shared_ptr<const Msg>(p.get(), [p](const Msg*) {}));
                 },
                 [](ros::NodeHandle& nh, const std::string& topic, std::function<void(Received)> done) {
                   return subscribeOf<Msg>(nh, topic, std::move(done), [](const boost::shared_ptr<const Msg>& msg) {
                     return apex::Message::share<Msg>(std::shared_ptr<const Msg>(msg.get(), [msg](const Msg*) {}));
                   });
                 },
                 [](const apex::Message& m) -> std::optional<ros::Time> {
                   if (auto p = m.as<Msg>()) return p->header.stamp;
                   return std::nullopt;
                 }};
}

RosType image() {
  return RosType{"sensor_msgs/Image",
                 apex::typeOf<Image>(),
                 advertiseOf<sensor_msgs::Image>,
                 [](const ros::Publisher& pub, const apex::Message& m) {
                   if (auto p = m.as<Image>()) pub.publish(toRos(*p));  // copies the pixels into the message (cv_bridge)
                 },
                 [](ros::NodeHandle& nh, const std::string& topic, std::function<void(Received)> done) {
                   return subscribeOf<sensor_msgs::Image>(nh, topic, std::move(done), [](const sensor_msgs::ImageConstPtr& msg) {
                     return apex::Message::share<Image>(fromRos(msg));  // shares the message's pixels
                   });
                 },
                 [](const apex::Message& m) -> std::optional<ros::Time> {
                   if (auto p = m.as<Image>()) return p->header.stamp;
                   return std::nullopt;
                 }};
}

/** A cloud as the message a nodelet subscribes to: a copy of its points (a PointCloud2 owns its
 *  data). Published as a Cloud instead, roscpp would serialise it for the nodelet's PointCloud2
 *  callback and deserialise it there: two copies. */
sensor_msgs::PointCloud2Ptr toPointCloud2(const Cloud& cloud) {
  auto msg = boost::make_shared<sensor_msgs::PointCloud2>();
  if (cloud.points) pcl_conversions::fromPCL(*cloud.points, *msg);
  msg->header = cloud.header;  // exact: PCL's header keeps microseconds only
  return msg;
}

RosType cloud() {
  return RosType{"sensor_msgs/PointCloud2",
                 apex::typeOf<Cloud>(),
                 advertiseOf<sensor_msgs::PointCloud2>,
                 [](const ros::Publisher& pub, const apex::Message& m) {
                   if (auto p = m.as<Cloud>()) pub.publish(toPointCloud2(*p));
                 },
                 [](ros::NodeHandle& nh, const std::string& topic, std::function<void(Received)> done) {
                   return subscribeOf<sensor_msgs::PointCloud2>(
                       nh, topic, std::move(done), [](const sensor_msgs::PointCloud2ConstPtr& msg) {
                         return apex::Message::share<Cloud>(fromRos(msg));  // copies the points into PCL's layout
                       });
                 },
                 [](const apex::Message& m) -> std::optional<ros::Time> {
                   if (auto p = m.as<Cloud>()) return p->header.stamp;
                   return std::nullopt;
                 }};
}

const std::vector<RosType>& rosTypes() {
  static const std::vector<RosType> kTypes{image(), cloud(), itself<sensor_msgs::CameraInfo>("sensor_msgs/CameraInfo"),
                                           itself<sensor_msgs::LaserScan>("sensor_msgs/LaserScan")};
  return kTypes;
}

/** The port's name for a topic: "left/image_raw" -> "left_image_raw". */
std::string portName(std::string topic) {
  if (!topic.empty() && topic.front() == '/') topic.erase(0, 1);
  for (char& c : topic)
    if (c == '/') c = '_';
  return topic;
}

apex::Result<PortTopic> parsePort(const std::string& entry, const std::string& what) {
  auto bad = [&](const std::string& why) { return apex::Status::error(what + ": '" + entry + "' " + why); };
  const auto colon = entry.rfind(':');
  if (colon == std::string::npos) return bad("is not topic:type (e.g. image_mono:sensor_msgs/Image)");
  PortTopic p{entry.substr(0, colon), portName(entry.substr(0, colon)), findRosType(entry.substr(colon + 1))};
  std::string why;
  if (p.topic.empty() || p.topic.back() == '/' || !ros::names::validate(p.topic, why) || p.topic.front() == '~')
    return bad("does not name a topic as the nodelet subscribes or advertises it (relative or /absolute, no ~)" +
               (why.empty() ? "" : ": " + why));
  if (!p.type) return bad("has a type ports cannot carry yet; they carry " + rosTypeNames());
  return p;
}

}  // namespace

const RosType* findRosType(const std::string& name) {
  for (const auto& t : rosTypes())
    if (t.name == name) return &t;
  return nullptr;
}

std::string rosTypeNames() {
  std::string out;
  for (const auto& t : rosTypes()) out += (out.empty() ? "" : ", ") + t.name;
  return out;
}

apex::Result<std::vector<PortTopic>> parsePorts(const std::vector<std::string>& entries, const std::string& what) {
  std::vector<PortTopic> out;
  for (const auto& e : entries) {
    auto p = parsePort(e, what);
    if (!p) return p.status();
    for (const auto& q : out)
      if (q.port == p->port)
        return apex::Status::error(what + ": '" + q.topic + "' and '" + p->topic + "' make one port, '" + q.port + "'");
    out.push_back(*p);
  }
  return out;
}

}  // namespace nodelet_host
}  // namespace apex_nodes
