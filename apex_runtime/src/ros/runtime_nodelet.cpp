// The same host as a nodelet (apex/Runtime), to share zero-copy messages with
// driver nodelets in one manager.
#include <ros/ros.h>
// (ros.h first: nodelet.h needs it)
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>

#include "apex/ros/runtime_host.hpp"

namespace apex {
namespace ros_host {

class RuntimeNodelet : public nodelet::Nodelet {
 private:
  void onInit() override { host_ = std::make_unique<RuntimeHost>(getMTNodeHandle(), getMTPrivateNodeHandle()); }
  std::unique_ptr<RuntimeHost> host_;
};

}  // namespace ros_host
}  // namespace apex

PLUGINLIB_EXPORT_CLASS(apex::ros_host::RuntimeNodelet, nodelet::Nodelet)
