// Latch: holds the last message that came and sends it at every firing, also when its input gets
// Nothing (e.g. the last detection, or a goal that arrives once), until `reset`.
#include "apex/core/registry.hpp"
#include "apex_nodes/flow.hpp"

namespace apex_nodes {

class Latch : public StatefulFlowNode {
 public:
  static inline const apex::InputPort<apex::Any> kIn{"in", "any message, or Nothing: the message held stays", true};
  static inline const apex::OutputPort<apex::Any> kOut{
      "out", "the last message `in` received (the same object); Nothing before the first and after `reset`"};
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Holds the last message (not Nothing) of its input and sends it at every firing until `reset`, as a latched "
               "topic keeps its last message")
        .inCategory("flow")
        .input(kIn)
        .output(kOut)
        .slot("reset", &Latch::reset, "forgets the message held: Nothing until the next one; the end of a sequence does too");
  }
  void process() override {
    if (in_.has()) held_ = in_.message();
    if (!held_.isNothing()) out_.publishMessage(held_);
  }
  void reset() override { held_ = apex::Message(); }

 private:
  apex::Input<apex::Any> in_{this, kIn};
  apex::Output<apex::Any> out_{this, kOut};
  apex::Message held_;  // Nothing until a message came
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Latch, "apex_nodes/Latch");
