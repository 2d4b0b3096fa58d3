// FieldExtract: one numeric field of any ROS message, by path, as a number: odometry or IMU values
// drive parameters and plots. It reads the message's serialized bytes with its definition
// (message_fields.hpp): a RosMessage as it came, any other message as its inspector serializes it
// (a pose, a scan, camera info...). The path is checked once per message type and path.
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "apex/core/registry.hpp"
#include "apex/ros/inspect.hpp"
#include "apex_nodes/ros_message.hpp"
#include "message_fields.hpp"

namespace apex_nodes {

class FieldExtract : public apex::Node {
 public:
  static inline const apex::InputPort<apex::Any> kMessage{
      "message", "a ROS message (TopicSubscriber, BagReader), or any message with a ROS form (a pose, a scan, camera info...)"};
  static inline const apex::OutputPort<double> kValue{"value", "the field's value; a time or duration in seconds, a bool 0 or 1"};
  static inline const apex::ParamDecl<std::string> kField =
      apex::param::text("field")
          .init("header.stamp")
          .describe("a path: pose.pose.position.x, linear_acceleration.z, ranges[3], header.stamp (or header.stamp.secs)");
  static apex::Manifest manifest() {
    return apex::Manifest("Takes one numeric field of any ROS message by path (pose.pose.position.x, ranges[3]) as a number")
        .inCategory("ROS I/O")
        .input(kMessage)
        .output(kValue)
        .param(kField);
  }

  void parameterChanged(const std::string&) override { readers_.clear(); }
  void process() override {
    const apex::Message& m = in_.message();
    if (m.isNothing()) return;
    if (auto p = m.as<RosMessage>()) {
      value_.publish(reader(p->datatype, p->md5sum, p->definition).read(p->bytes.data(), p->bytes.size()));
      return;
    }
    const apex::SerializedMessage s = serializer(m)(m);
    value_.publish(reader(s.datatype, s.md5sum, s.definition).read(s.bytes.data(), s.bytes.size()));
  }

 private:
  /** The field's reader for messages of this type (parsed once per type and path). */
  const FieldReader& reader(const std::string& datatype, const std::string& md5sum, const std::string& definition) {
    const std::string key = datatype + " " + md5sum;
    auto it = readers_.find(key);
    if (it != readers_.end()) return it->second;
    if (readers_.size() >= 16) readers_.clear();  // inputs of ever new types: stay small
    auto schema = std::make_shared<const MessageSchema>(datatype, definition);
    return readers_.emplace(key, FieldReader(std::move(schema), field_.get())).first->second;
  }
  /** How messages of m's type become ROS messages (found once per type); an error if they do not. */
  const std::function<apex::SerializedMessage(const apex::Message&)>& serializer(const apex::Message& m) {
    if (m.type() == serialized_type_) return serialize_;
    auto serialize = apex::findInspector(m.type()).serialize;
    if (!serialize) {
      std::string types;
      for (const auto& t : apex::inspectedTypes()) types += (types.empty() ? "" : ", ") + t;
      throw std::invalid_argument("input 'message' carries " + m.typeName() + ", which has no ROS message to read a field of " +
                                  "(these types have one: " + types + ")");
    }
    serialize_ = std::move(serialize);
    serialized_type_ = m.type();
    return serialize_;
  }

  apex::Input<apex::Any> in_{this, kMessage};
  apex::Output<double> value_{this, kValue};
  apex::Param<std::string> field_{this, kField};
  std::map<std::string, FieldReader> readers_;  // by "datatype md5sum", for field_
  const apex::TypeInfo* serialized_type_ = nullptr;
  std::function<apex::SerializedMessage(const apex::Message&)> serialize_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::FieldExtract, "apex_nodes/FieldExtract");
