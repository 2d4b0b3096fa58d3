// Counter: counts the messages it receives; a slot resets it.
#include "apex/core/registry.hpp"

namespace apex_nodes {

class Counter : public apex::Node {
 public:
  static inline const apex::InputPort<apex::Any> kIn{"in", "any message"};
  static inline const apex::OutputPort<int> kCount{"count", "messages received since the last reset"};
  static apex::Manifest manifest() {
    return apex::Manifest("Counts the messages it receives")
        .inCategory("flow")
        .keepsState("its count: a re-run counts the held frame again")
        .input(kIn)
        .output(kCount)
        .slot("reset", &Counter::reset, "sets the count to zero");
  }
  void process() override { count_.publish(++received_); }
  void reset() { received_ = 0; }

 private:
  apex::Output<int> count_{this, kCount};
  int received_ = 0;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Counter, "apex_nodes/Counter");
