// Clock: a source at a rate, from its thread group's timer.
#include <chrono>

#include "apex/core/registry.hpp"

namespace apex_nodes {

class Clock : public apex::Node {
 public:
  static inline const apex::OutputPort<int> kCount{"count", "0, 1, 2, ..."};
  static inline const apex::OutputPort<double> kTime{"time", "seconds since the first tick"};
  static inline const apex::ParamDecl<double> kRate =
      apex::param::number("rate").range(0.01, 1000.0).step(0.01).init(10.0).describe("ticks per second");
  static apex::Manifest manifest() {
    return apex::Manifest("Ticks at a rate: a counter and the time since it started")
        .inCategory("flow")
        .output(kCount)
        .output(kTime)
        .param(kRate)
        .driven();
  }
  void setup() override {
    start_ = std::chrono::steady_clock::now();
    notifyNewData();
  }
  void process() override {
    count_.publish(ticks_++);
    time_.publish(std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
    notifyAfter(1.0 / rate_.get());
  }

 private:
  apex::Output<int> count_{this, kCount};
  apex::Output<double> time_{this, kTime};
  apex::Param<double> rate_{this, kRate};
  int ticks_ = 0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Clock, "apex_nodes/Clock");
