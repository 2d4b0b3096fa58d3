// Compare: a number against a threshold, as a bool for Switch or Select, and as events when the
// answer changes (e.g. "the battery fell below 20 %").
#include <cmath>
#include <string>

#include "apex/core/registry.hpp"
#include "apex_nodes/flow.hpp"

namespace apex_nodes {
namespace param = apex::param;
namespace {

/** Equal and not_equal's test; v == t: equal infinities. */
bool within(double v, double t, double tolerance) { return std::fabs(v - t) <= tolerance || v == t; }

}  // namespace

class Compare : public StatefulFlowNode {
 public:
  static inline const apex::InputPort<apex::Any> kValue{"value", "an int or a double; anything else is an error"};
  static inline const apex::OutputPort<bool> kResult{"result",
                                                     "whether `value` `operator` `threshold` holds, e.g. value less 0.5"};
  static inline const apex::TriggerPort kRose{
      "rose", "fires when the result turns true (also at the first value, as a PLC's R_TRIG: it counts as false before)"};
  static inline const apex::TriggerPort kFell{"fell", "fires when the result turns false"};
  /** Whether `value` (v) stands in an operator's relation to `threshold` (t), within `tolerance`. */
  using Holds = bool (*)(double v, double t, double tolerance);
  static inline const apex::ChoiceDecl<Holds> kOperator =
      param::choice<Holds>("operator",
                           {{"greater", [](double v, double t, double) { return v > t; }},
                            {"greater_equal", [](double v, double t, double) { return v >= t; }},
                            {"less", [](double v, double t, double) { return v < t; }},
                            {"less_equal", [](double v, double t, double) { return v <= t; }},
                            {"equal", [](double v, double t, double tolerance) { return within(v, t, tolerance); }},
                            {"not_equal", [](double v, double t, double tolerance) { return !within(v, t, tolerance); }}})
          .describe("how `value` is compared with `threshold`");
  static inline const apex::ParamDecl<double> kThreshold = param::number("threshold").describe("the value compared against");
  static inline const apex::ParamDecl<double> kTolerance =
      param::number("tolerance")
          .range(0.0, 1e9)
          .describe("equal and not_equal: values within this distance of `threshold` count as equal");
  static apex::Manifest manifest() {
    return apex::Manifest("Compares a number with a threshold: the answer as a bool, and events when it changes")
        .inCategory("flow")
        .input(kValue)
        .output(kResult)
        .param(kOperator)
        .param(kThreshold)
        .param(kTolerance)
        .trigger(kRose)
        .trigger(kFell)
        .slot("reset", &Compare::reset,
              "forgets the last result (false again, so a true next fires `rose`); the end of a sequence does too");
  }
  void process() override {
    const bool now = operator_.get()(numberOf(value_.message(), kValue.name), threshold_.get(), tolerance_.get());
    result_.publish(now);
    if (now && !last_) rose_.fire();
    if (!now && last_) fell_.fire();
    last_ = now;
  }
  void reset() override { last_ = false; }

 private:
  apex::Input<apex::Any> value_{this, kValue};
  apex::Output<bool> result_{this, kResult};
  apex::Trigger rose_{this, kRose};
  apex::Trigger fell_{this, kFell};
  apex::Choice<Holds> operator_{this, kOperator};
  apex::Param<double> threshold_{this, kThreshold};
  apex::Param<double> tolerance_{this, kTolerance};
  bool last_ = false;  // the last result; false before the first
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Compare, "apex_nodes/Compare");
