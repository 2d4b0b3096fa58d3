// Statistics: mean, standard deviation, minimum and maximum of a number over its last N values
// (e.g. a detector's latency, a range's noise).
#include <algorithm>
#include <cmath>
#include <deque>
#include <numeric>

#include "apex/core/registry.hpp"
#include "apex_nodes/flow.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Statistics : public StatefulFlowNode {
 public:
  static inline const apex::InputPort<apex::Any> kValue{"value", "an int or a double; anything else is an error"};
  static inline const apex::OutputPort<double> kMean{"mean", "the mean of the values in the window"};
  static inline const apex::OutputPort<double> kStd{
      "std", "their standard deviation (of the population: divided by count, as numpy.std); 0 for one value"};
  static inline const apex::OutputPort<double> kMin{"min", "the smallest value in the window"};
  static inline const apex::OutputPort<double> kMax{"max", "the largest value in the window"};
  static inline const apex::OutputPort<int> kCount{"count", "how many values the window holds (up to `window`)"};
  static inline const apex::ParamDecl<int> kWindow =
      param::integer("window").range(1, 100000).step(1).init(10).describe("how many of the last values are counted");
  static apex::Manifest manifest() {
    return apex::Manifest("Mean, standard deviation, minimum and maximum of a number over its last `window` values")
        .inCategory("flow")
        .keepsState("the values so far: a re-run counts the held frame again")
        .input(kValue)
        .output(kMean)
        .output(kStd)
        .output(kMin)
        .output(kMax)
        .output(kCount)
        .param(kWindow)
        .slot("reset", &Statistics::reset, "forgets the values: the window starts empty; the end of a sequence does too");
  }
  void process() override {
    pushWithin(values_, numberOf(value_.message(), kValue.name), static_cast<std::size_t>(window_.get()));
    const double n = static_cast<double>(values_.size());
    const double mean = std::accumulate(values_.begin(), values_.end(), 0.0) / n;
    double squares = 0;
    for (double v : values_) squares += (v - mean) * (v - mean);
    const auto [low, high] = std::minmax_element(values_.begin(), values_.end());
    mean_.publish(mean);
    std_.publish(std::sqrt(squares / n));
    min_.publish(*low);
    max_.publish(*high);
    count_.publish(static_cast<int>(values_.size()));
  }
  void reset() override { values_.clear(); }

 private:
  apex::Input<apex::Any> value_{this, kValue};
  apex::Output<double> mean_{this, kMean};
  apex::Output<double> std_{this, kStd};
  apex::Output<double> min_{this, kMin};
  apex::Output<double> max_{this, kMax};
  apex::Output<int> count_{this, kCount};
  apex::Param<int> window_{this, kWindow};
  std::deque<double> values_;  // the last `window` values, oldest first
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Statistics, "apex_nodes/Statistics");
