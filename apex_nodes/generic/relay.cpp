// Relay: passes any message through unchanged (the same object, no copy).
#include "apex/core/registry.hpp"

namespace apex_nodes {

class Relay : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Passes any message through unchanged")
        .input<apex::Any>("in", "any message")
        .output<apex::Any>("out", "the same message");
  }
  void process() override { out_.publishMessage(in_.message()); }

 private:
  apex::Input<apex::Any> in_{this, "in"};
  apex::Output<apex::Any> out_{this, "out"};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Relay, "apex_nodes/Relay");
