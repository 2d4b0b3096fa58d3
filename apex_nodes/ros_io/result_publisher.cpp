// ResultPublisher: publishes any message that has a ROS form on a topic: the form ~inspect shows
// and BagWriter records (apex/ros/inspect.hpp): regions, contours, lines, circles, markers,
// corners, keypoints, matches, homographies and tracks as this package's messages (ros_results.hpp),
// images, clouds, scans, numbers and text as theirs. Its input takes any type, so the topic is
// advertised at the first message, as that message's ROS type; a message of another type later
// (the input reconnected) advertises the topic again as the new type. Like the publishers of
// topic_sink.hpp, a message is converted only while someone subscribes.
#include <ros/ros.h>

#include <stdexcept>
#include <string>
#include <utility>

#include "apex/core/registry.hpp"
#include "apex/ros/inspect.hpp"
#include "apex/ros/node_handles.hpp"

namespace apex_nodes {

class ResultPublisher : public apex::Node {
 public:
  static inline const apex::InputPort<apex::Any> kIn{
      "in", "any message with a ROS form (one ~inspect shows): the first decides the topic's type"};
  static inline const apex::ParamDecl<std::string> kTopic =
      apex::param::text("topic").init("results").describe("resolved in the runtime's namespace");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Publishes any message that has a ROS form (regions, contours, keypoints, matches, images, clouds, "
               "numbers...) on a topic, as ~inspect shows it; a message of another type advertises the topic anew")
        .inCategory("ROS I/O")
        .input(kIn)
        .param(kTopic);
  }

  void parameterChanged(const std::string& name) override {
    if (name == kTopic.name() && type_) advertise();
  }
  void process() override {
    const apex::Message& m = in_.message();
    if (m.isNothing()) return;
    if (m.type() != type_) {
      apex::Inspector inspector = apex::findInspector(m.type());
      if (!inspector.serialize) throw std::invalid_argument(m.typeName() + " has no ROS form to publish; " + formsText());
      inspector_ = std::move(inspector);
      type_ = m.type();
      advertise();
    }
    if (pub_.getNumSubscribers() > 0) inspector_.publish(pub_, m);
  }

 private:
  /** (Re)advertises the topic as the current type: the old publisher goes first, as a process
   *  cannot advertise one topic as two types. */
  void advertise() {
    pub_.shutdown();
    ros::NodeHandle nh = apex::nodeHandle(*this);
    pub_ = inspector_.advertise(nh, topic_.get(), ros::SubscriberStatusCallback());
    if (!pub_) {
      const std::string type = inspector_.message_type;
      type_ = nullptr;  // the next message tries again
      throw std::runtime_error("cannot advertise '" + topic_.get() + "' as " + type +
                               ": this process publishes it as another type");
    }
  }
  static std::string formsText() {
    std::string out = "these types have one:";
    const auto types = apex::inspectedTypes();
    for (std::size_t i = 0; i < types.size(); ++i) out += (i == 0 ? " " : ", ") + types[i];
    return out;
  }

  apex::Input<apex::Any> in_{this, kIn};
  apex::Param<std::string> topic_{this, kTopic};
  const apex::TypeInfo* type_ = nullptr;  // the type the topic is advertised as; none before the first message
  apex::Inspector inspector_;
  ros::Publisher pub_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::ResultPublisher, "apex_nodes/ResultPublisher");
