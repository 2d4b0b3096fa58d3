// Relay: passes any message through unchanged (the same object, no copy).
#include "apex/core/registry.hpp"

namespace apex_nodes {

class Relay : public apex::Node {
 public:
  static inline const apex::InputPort<apex::Any> kIn{"in", "any message"};
  static inline const apex::OutputPort<apex::Any> kOut{"out", "the same message"};
  static apex::Manifest manifest() {
    return apex::Manifest("Passes any message through unchanged").inCategory("flow").input(kIn).output(kOut);
  }
  void process() override { out_.publishMessage(in_.take()); }

 private:
  apex::Input<apex::Any> in_{this, kIn};
  apex::Output<apex::Any> out_{this, kOut};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Relay, "apex_nodes/Relay");
