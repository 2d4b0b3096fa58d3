// TfLookup: the tf2 transform between two frames at a message's stamp.
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <memory>

#include "apex/ros/inspect.hpp"
#include "apex/core/registry.hpp"
#include "apex/ros/node_handles.hpp"
#include "apex_nodes/stamp.hpp"

namespace apex_nodes {

class TfLookup : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Looks up the transform from the message's frame (or source_frame) to target_frame at its stamp")
        .input<apex::Any>("stamped", "an image, cloud, regions, clusters or scan: its header gives frame and time")
        .output<geometry_msgs::TransformStamped>("transform", "maps points of the source frame into the target frame")
        .param(apex::param::text("target_frame", "base_link"))
        .param(apex::param::text("source_frame", "").describe("empty: the message's frame_id"))
        .param(apex::param::range("timeout", 0.0, 10.0, 0.01, 0.1).describe("seconds to wait for the transform"));
  }
  void setup() override {
    buffer_ = std::make_unique<tf2_ros::Buffer>();
    listener_ = std::make_unique<tf2_ros::TransformListener>(*buffer_, apex::nodeHandle(*this));
  }
  void process() override {
    const auto header = headerOf(inputMessage("stamped"));
    if (!header) throw std::invalid_argument("a " + inputMessage("stamped").typeName() + " has no header to look up");
    const std::string source = param<std::string>("source_frame").empty() ? header->frame_id : param<std::string>("source_frame");
    try {
      publish("transform", buffer_->lookupTransform(param<std::string>("target_frame"), source, header->stamp,
                                                    ros::Duration(param<double>("timeout"))));
    } catch (const tf2::TransformException& e) {
      throw std::runtime_error("no transform " + source + " -> " + param<std::string>("target_frame") + " at " +
                               std::to_string(header->stamp.toSec()) + ": " + e.what());
    }
  }

 private:
  std::unique_ptr<tf2_ros::Buffer> buffer_;
  std::unique_ptr<tf2_ros::TransformListener> listener_;
};

const bool kInspectTransforms = apex::addInspector<geometry_msgs::TransformStamped, geometry_msgs::TransformStamped>(
    [](const geometry_msgs::TransformStamped& t) { return t; });

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::TfLookup, "apex_nodes/TfLookup");
