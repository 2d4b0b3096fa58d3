// Node types only the ROS tests use (test/ros/test_plugins.xml, given to the runtime as
// ~extra_plugin_xml): a separate plugin library, registered as any package's would be.
#include <chrono>
#include <condition_variable>
#include <mutex>

#include "apex/core/registry.hpp"
#include "apex/ros/node_library.hpp"

namespace apex_test_nodes {

/** Stays inside process() for `seconds`: a long computation that shutdown must not wait for. */
class Busy : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Stays inside process() for a while, then passes its input on")
        .input<apex::Any>("in")
        .output<apex::Any>("out")
        .param(apex::param::range("seconds", 0.0, 600.0, 0.1, 1.0));
  }
  ~Busy() override {
    std::lock_guard<std::mutex> lock(m_);
    gone_ = true;
    cv_.notify_all();
  }
  void process() override {
    log(apex::LogLevel::Info, "inside process() for " + std::to_string(seconds_.get()) + " s");
    std::unique_lock<std::mutex> lock(m_);  // the computation: over after `seconds`, or when the node goes
    cv_.wait_for(lock, std::chrono::duration<double>(seconds_.get()), [this] { return gone_; });
    out_.publishMessage(in_.message());
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  bool gone_ = false;
  apex::Input<apex::Any> in_{this, "in"};
  apex::Output<apex::Any> out_{this, "out"};
  apex::Param<double> seconds_{this, "seconds"};
};

}  // namespace apex_test_nodes

APEX_REGISTER_NODE(apex_test_nodes::Busy, "apex_test/Busy");
APEX_NODE_LIBRARY(apex_test_nodes)
