#include "apex/core/registry.hpp"

namespace demo {

// Multiplies an int by a tunable gain.
class Gain : public apex::Node {
 public:
  // Each port and parameter declared once, as a typed constant: the manifest lists it and a
  // handle reads it, so their names and types cannot disagree.
  static inline const apex::InputPort<int> kIn{"in", "the value"};
  static inline const apex::OutputPort<int> kOut{"out", "in times gain"};
  static inline const apex::ParamDecl<int> kGain = apex::param::integer("gain").range(-100, 100).init(2).describe("the factor");
  static inline const apex::TriggerPort kOverflow{"overflow", "fires when the result passes 1000"};

  static apex::Manifest manifest() {
    return apex::Manifest("Multiplies its input by a gain")
        .input(kIn)
        .output(kOut)
        .param(kGain)
        .trigger(kOverflow)
        .slot("reset", &Gain::reset, "forgets what it learned");
  }
  void process() override {
    const int out = *in_.get() * gain_.get();
    if (out > 1000) overflow_.fire();
    out_.publish(out);
  }
  void reset() {}  // runs on the node's thread group, never during process()

 private:
  // Typed handles, found by index at every use: `apex::Input<double> in_{this, kIn}` does not
  // compile (kIn carries int).
  apex::Input<int> in_{this, kIn};
  apex::Output<int> out_{this, kOut};
  apex::Param<int> gain_{this, kGain};
  apex::Trigger overflow_{this, kOverflow};
};

}  // namespace demo

APEX_REGISTER_NODE(demo::Gain, "demo/Gain");
