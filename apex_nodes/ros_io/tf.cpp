// TfLookup: the tf2 transform between two frames at a message's stamp, from the node's own buffer
// (TfListener, tf_listener.hpp).
#include <ros/ros.h>

#include <memory>

#include "apex/ros/inspect.hpp"
#include "apex/core/registry.hpp"
#include "apex_nodes/stamp.hpp"
#include "tf_listener.hpp"

namespace apex_nodes {

class TfLookup : public apex::Node {
 public:
  static inline const apex::InputPort<apex::Any> kStamped{
      "stamped", "an image, cloud, regions, clusters or scan: its header gives frame and time"};
  static inline const apex::OutputPort<geometry_msgs::TransformStamped> kTransform{
      "transform", "maps points of the source frame into the target frame"};
  static inline const apex::ParamDecl<std::string> kTargetFrame = apex::param::text("target_frame").init("base_link");
  static inline const apex::ParamDecl<std::string> kSourceFrame =
      apex::param::text("source_frame").describe("empty: the message's frame_id");
  static inline const apex::ParamDecl<double> kTimeout = tfTimeoutParam("seconds to wait for the transform");
  static apex::Manifest manifest() {
    return apex::Manifest("Looks up the transform from the message's frame (or source_frame) to target_frame at its stamp")
        .inCategory("ROS I/O")
        .input(kStamped)
        .output(kTransform)
        .param(kTargetFrame)
        .param(kSourceFrame)
        .param(kTimeout);
  }
  void setup() override { tf_ = std::make_unique<TfListener>(*this); }
  void process() override {
    const auto header = headerOf(stamped_.message());
    if (!header) throw std::invalid_argument("a " + stamped_.message().typeName() + " has no header to look up");
    const std::string source = source_frame_.get().empty() ? header->frame_id : source_frame_.get();
    const std::string& target = target_frame_.get();
    try {
      tf_->waitFor(target, source, header->stamp, timeout_.get());
      transform_.publish(tf_->buffer().lookupTransform(target, source, header->stamp));
    } catch (const tf2::TransformException& e) {
      throw std::runtime_error(noTransform(source, target, header->stamp) + ": " + e.what());
    }
  }

 private:
  apex::Input<apex::Any> stamped_{this, kStamped};
  apex::Output<geometry_msgs::TransformStamped> transform_{this, kTransform};
  apex::Param<std::string> target_frame_{this, kTargetFrame};
  apex::Param<std::string> source_frame_{this, kSourceFrame};
  apex::Param<double> timeout_{this, kTimeout};
  std::unique_ptr<TfListener> tf_;  // from setup(): on the runtime's node handle
};

const bool kInspectTransforms = apex::addInspector<geometry_msgs::TransformStamped, geometry_msgs::TransformStamped>(
    [](const geometry_msgs::TransformStamped& t) { return t; });

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::TfLookup, "apex_nodes/TfLookup");
