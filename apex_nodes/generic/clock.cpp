// Clock: a source at a rate, from its thread group's timer.
#include <chrono>

#include "apex/core/registry.hpp"

namespace apex_nodes {

class Clock : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Ticks at a rate: a counter and the time since it started")
        .output<int>("count", "0, 1, 2, ...")
        .output<double>("time", "seconds since the first tick")
        .param(apex::param::range("rate", 0.01, 1000.0, 0.01, 10.0).describe("ticks per second"))
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
  apex::Output<int> count_{this, "count"};
  apex::Output<double> time_{this, "time"};
  apex::Param<double> rate_{this, "rate"};
  int ticks_ = 0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Clock, "apex_nodes/Clock");
