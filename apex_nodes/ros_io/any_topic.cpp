// TopicSubscriber and TopicPublisher: topics of any message type. The subscriber receives any
// type (as topic_tools' ShapeShifter does: RosMessage is a message of any type, ros_message.hpp)
// and sends it on as it came, or converted to the library's port type when `type` names one it
// knows (sensor_msgs/Image → an Image). The publisher sends any message that has a ROS form: a
// RosMessage as itself, anything else as its inspector serializes it (apex/ros/inspect.hpp);
// the first message decides the topic's type, as ROS cannot change it later.
#include <ros/ros.h>

#include <boost/shared_ptr.hpp>

#include <optional>
#include <stdexcept>
#include <string>

#include "apex/core/registry.hpp"
#include "apex/ros/inspect.hpp"
#include "apex/ros/node_handles.hpp"
#include "apex_nodes/ros_message.hpp"
#include "topic_source.hpp"

namespace apex_nodes {
namespace {

/** "nav_msgs/Odometry": a package and a name. */
bool isRosType(const std::string& type) {
  const auto slash = type.find('/');
  return slash != std::string::npos && slash > 0 && slash + 1 < type.size() && type.find('/', slash + 1) == std::string::npos &&
         type.find_first_of(" \t[]") == std::string::npos;
}

/** The `message` output, typed by `type`: the library's port type for it, else RosMessage. */
apex::Status shapeOutput(const apex::ParamValues& p, apex::Manifest& m) {
  const std::string& type = p.get<std::string>("type");
  if (!type.empty() && !isRosType(type))
    return apex::Status::error("type '" + type + "' is not a ROS message type (package/Name, e.g. nav_msgs/Odometry)");
  for (apex::PortSpec& out : m.outputs) {
    if (out.name != "message") continue;
    out.type = type.empty() ? apex::typeOf<RosMessage>() : portType(type);
    if (out.type != apex::typeOf<RosMessage>()) out.description = "the topic's " + type + " messages as " + out.type->name;
    else if (!type.empty()) out.description = "the topic's " + type + " messages as received";
  }
  return apex::Status::ok();
}

std::string inspectedTypesText() {
  std::string out;
  for (const auto& t : apex::inspectedTypes()) out += (out.empty() ? "" : ", ") + t;
  return out;
}

}  // namespace

class TopicSubscriber : public TopicSource<RosMessage> {
 public:
  static inline const apex::OutputPort<RosMessage> kMessage{"message", "each message of the topic as received"};
  static inline const apex::ParamDecl<std::string> kTopic =
      apex::param::text("topic").init("input").describe("resolved in the runtime's namespace");
  static inline const apex::ParamDecl<std::string> kType =
      apex::param::text("type")
          .describe(
              "the topic's message type, e.g. nav_msgs/Odometry (a message of another type is an error); one the "
              "library has a port type for arrives converted (sensor_msgs/Image: an Image); empty: any type, as received")
          .shapesInterface();
  static apex::Manifest manifest() {
    return apex::Manifest("Receives a topic of any message type (as topic_tools' relay does); keeps only the newest")
        .inCategory("ROS I/O")
        .output(kMessage)
        .param(kTopic)
        .param(kType)
        .param(holdParam())
        .shapedBy(shapeOutput)
        .keepsNewest();
  }

 private:
  void subscribe() override {
    sub_ = apex::nodeHandle(*this).subscribe<RosMessage>(topic_.get(), kQueue, [this](const MsgPtr& m) { received(m); });
  }
  void send(const MsgPtr& msg) override {
    const std::string& type = type_.get();
    if (!type.empty() && msg->datatype != type)
      throw std::invalid_argument("topic '" + sub_.getTopic() + "' carries " + msg->datatype + ", not " + type +
                                  " (the parameter 'type')");
    std::shared_ptr<const RosMessage> shared(msg.get(), [msg](const RosMessage*) {});  // the pointer keeps ROS's message
    publishMessage(kMessage.name, type.empty() ? apex::Message::share<RosMessage>(shared) : toPort(shared));
  }
  apex::Param<std::string> topic_{this, kTopic};
  apex::Param<std::string> type_{this, kType};
  ros::Subscriber sub_;
};

class TopicPublisher : public apex::Node {
 public:
  static inline const apex::InputPort<apex::Any> kMessage{
      "message",
      "a ROS message, or any message with a ROS form (an image, a pose, a number...): the first decides the topic's type"};
  static inline const apex::ParamDecl<std::string> kTopic =
      apex::param::text("topic").init("output").describe("resolved in the runtime's namespace");
  static inline const apex::ParamDecl<bool> kLatch =
      apex::param::flag("latch").describe("keep the last message for subscribers that come later (as rostopic pub --latch)");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Publishes any ROS message, or any message with a ROS form, on a topic of its type; the first message "
               "decides the type")
        .inCategory("ROS I/O")
        .input(kMessage)
        .param(kTopic)
        .param(kLatch);
  }

  void parameterChanged(const std::string&) override {  // the next message advertises anew
    pub_.shutdown();
    advertised_.reset();
  }
  void process() override {
    const apex::Message& m = in_.message();
    if (m.isNothing()) return;
    if (advertised_ && datatypeOf(m) != advertised_->datatype)
      throw std::invalid_argument("topic '" + pub_.getTopic() + "' is advertised as " + advertised_->datatype +
                                  "; this message is " + datatypeOf(m) +
                                  " (ROS cannot change a topic's type: set the topic again, or another one)");
    if (advertised_ && !latch_.get() && pub_.getNumSubscribers() == 0) return;  // nobody listens: no conversion
    const std::shared_ptr<const RosMessage> msg = rosMessage(m);
    if (!advertised_) advertise(*msg);
    if (msg->md5sum != advertised_->md5sum)
      throw std::invalid_argument("topic '" + pub_.getTopic() + "' is advertised as " + advertised_->datatype + " of MD5 " +
                                  advertised_->md5sum + "; this message's definition differs (MD5 " + msg->md5sum + ")");
    pub_.publish(boost::shared_ptr<const RosMessage>(msg.get(), [msg](const RosMessage*) {}));  // shared in-process
  }

 private:
  struct Advertised {
    std::string datatype, md5sum;
  };
  /** The message's ROS type, without converting it. */
  std::string datatypeOf(const apex::Message& m) {
    if (auto p = m.as<RosMessage>()) return p->datatype;
    return inspector(m).message_type;
  }
  /** The message as a ROS message: itself, or serialized by its inspector. */
  std::shared_ptr<const RosMessage> rosMessage(const apex::Message& m) {
    if (auto p = m.as<RosMessage>()) return p;
    apex::SerializedMessage s = inspector(m).serialize(m);
    return std::make_shared<const RosMessage>(RosMessage{s.datatype, s.md5sum, s.definition, std::move(s.bytes)});
  }
  /** The inspector of m's type (found once per type); an error for a type with no ROS form. */
  const apex::Inspector& inspector(const apex::Message& m) {
    if (m.type() != inspected_type_) {
      apex::Inspector i = apex::findInspector(m.type());
      if (!i.serialize)
        throw std::invalid_argument(m.typeName() +
                                    " has no ROS message to publish; these types have one: " + inspectedTypesText());
      inspector_ = std::move(i);
      inspected_type_ = m.type();
    }
    return inspector_;
  }
  void advertise(const RosMessage& m) {
    ros::AdvertiseOptions options(topic_.get(), 1, m.md5sum, m.datatype, m.definition);
    options.latch = latch_.get();
    ros::NodeHandle nh = apex::nodeHandle(*this);
    pub_ = nh.advertise(options);
    if (!pub_)
      throw std::runtime_error("cannot advertise '" + topic_.get() + "' as " + m.datatype +
                               ": this process publishes it as another type");
    advertised_ = Advertised{m.datatype, m.md5sum};
  }

  apex::Input<apex::Any> in_{this, kMessage};
  apex::Param<std::string> topic_{this, kTopic};
  apex::Param<bool> latch_{this, kLatch};
  ros::Publisher pub_;
  std::optional<Advertised> advertised_;  // none until the first message (and after a parameter changes)
  const apex::TypeInfo* inspected_type_ = nullptr;
  apex::Inspector inspector_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::TopicSubscriber, "apex_nodes/TopicSubscriber");
APEX_REGISTER_NODE(apex_nodes::TopicPublisher, "apex_nodes/TopicPublisher");
