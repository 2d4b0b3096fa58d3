// Switch: a branch opened and closed by a bool of the same frame, e.g. Compare's result.
#include "apex/core/registry.hpp"

namespace apex_nodes {

class Switch : public apex::Node {
 public:
  static inline const apex::InputPort<apex::Any> kIn{"in", "any message"};
  static inline const apex::InputPort<bool> kCondition{"condition", "true: `in` passes; false: Nothing"};
  static inline const apex::OutputPort<apex::Any> kOut{"out", "`in` (the same object) while `condition` is true, else Nothing"};
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Passes `in` to `out` while `condition` is true and sends Nothing while it is false. The condition is data of "
               "the same frame, so the branch opens and closes in step with the messages; the built-in enable/disable slots "
               "instead switch the whole node by events, which take effect between firings, at no particular frame")
        .inCategory("flow")
        .input(kIn)
        .input(kCondition)
        .output(kOut);
  }
  void process() override {
    if (*condition_.get()) out_.publishMessage(in_.take());
  }

 private:
  apex::Input<apex::Any> in_{this, kIn};
  apex::Input<bool> condition_{this, kCondition};
  apex::Output<apex::Any> out_{this, kOut};
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Switch, "apex_nodes/Switch");
