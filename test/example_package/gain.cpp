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
    const int out = *input<int>("in") * param<int>("gain");
    if (out > 1000) trigger("overflow");
    publish("out", out);
  }
  void reset() { /* runs on the node's thread group, never during process() */ }
};

}  // namespace demo

APEX_REGISTER_NODE(demo::Gain, "demo/Gain");
