// TfBroadcaster: a fixed transform between two frames, on tf2's /tf_static (a sensor's mounting,
// as static_transform_publisher gives it), sent again whenever a parameter changes.
#include <tf2/LinearMath/Quaternion.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <memory>

#include "apex/core/registry.hpp"
#include "apex/ros/node_handles.hpp"
#include "apex_nodes/stamp.hpp"

namespace apex_nodes {
namespace param = apex::param;

/** One coordinate of the child's origin. */
apex::ParamDecl<double> offset(const char* axis) {
  return param::number(axis).range(-1000.0, 1000.0).step(0.001).describe("the child's origin in the parent, metres");
}

class TfBroadcaster : public apex::Node {
 public:
  static inline const apex::ParamDecl<std::string> kParent = param::text("parent_frame").init("base_link");
  static inline const apex::ParamDecl<std::string> kChild = param::text("child_frame").init("camera");
  static inline const apex::ParamDecl<double> kX = offset("x"), kY = offset("y"), kZ = offset("z");
  static inline const apex::ParamDecl<double> kRoll = param::angle("roll"), kPitch = param::angle("pitch"),
                                              kYaw = param::angle("yaw");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Broadcasts a fixed transform parent_frame -> child_frame on /tf_static (roll, pitch, yaw about "
               "the parent's fixed x, y, z axes, as static_transform_publisher)")
        .inCategory("ROS I/O")
        .param(kParent)
        .param(kChild)
        .param(kX)
        .param(kY)
        .param(kZ)
        .param(kRoll)
        .param(kPitch)
        .param(kYaw);
  }
  void setup() override {
    if (!ros::isInitialized()) throw std::runtime_error("needs ROS: run it in the ROS runtime");
    broadcaster_ = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
    broadcast();
  }
  void parameterChanged(const std::string&) override {
    if (broadcaster_) broadcast();
  }
  void process() override {}  // no inputs: it never fires

 private:
  void broadcast() {
    if (parent_.get().empty() || child_.get().empty() || parent_.get() == child_.get())
      throw std::invalid_argument("needs two different frames, not '" + parent_.get() + "' and '" + child_.get() + "'");
    auto t = std::make_unique<geometry_msgs::TransformStamped>();
    t->header.stamp = ros::Time::now();
    t->header.frame_id = parent_.get();
    t->child_frame_id = child_.get();
    t->transform.translation.x = x_.get(), t->transform.translation.y = y_.get(), t->transform.translation.z = z_.get();
    tf2::Quaternion q;
    q.setRPY(roll_.get(), pitch_.get(), yaw_.get());
    t->transform.rotation.x = q.x(), t->transform.rotation.y = q.y(), t->transform.rotation.z = q.z(),
    t->transform.rotation.w = q.w();
    broadcaster_->sendTransform(*t);
  }
  apex::Param<std::string> parent_{this, kParent};
  apex::Param<std::string> child_{this, kChild};
  apex::Param<double> x_{this, kX}, y_{this, kY}, z_{this, kZ};
  apex::Param<double> roll_{this, kRoll}, pitch_{this, kPitch}, yaw_{this, kYaw};
  std::unique_ptr<tf2_ros::StaticTransformBroadcaster> broadcaster_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::TfBroadcaster, "apex_nodes/TfBroadcaster");
