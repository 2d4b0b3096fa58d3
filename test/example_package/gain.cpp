#include "apex/core/registry.hpp"

namespace demo {

// Multiplies an int by a tunable gain.
class Gain : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Multiplies its input by a gain")
        .input<int>("in")
        .output<int>("out")
        .param(apex::param::range("gain", -100, 100, 1, 2).describe("the factor"))
        .slot("reset", &Gain::reset, "forgets what it learned")
        .trigger("overflow", "fires when the result passes 1000");
  }
  void process() override {
    const int out = *in_.get() * gain_.get();
    if (out > 1000) overflow_.fire();
    out_.publish(out);
  }
  void reset() { /* runs on the node's thread group, never during process() */ }

 private:
  // Typed handles, resolved once: a name that manifest() lacks, or a wrong type, is refused
  // when the type is registered, saying what to write.
  apex::Input<int> in_{this, "in"};
  apex::Output<int> out_{this, "out"};
  apex::Param<int> gain_{this, "gain"};
  apex::Trigger overflow_{this, "overflow"};
};

}  // namespace demo

APEX_REGISTER_NODE(demo::Gain, "demo/Gain");
