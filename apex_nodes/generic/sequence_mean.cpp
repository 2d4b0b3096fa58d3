// SequenceMean: the mean of a value over a sequence, e.g. a detector's F1 over one pass of a
// bag. The end of the sequence arrives in step with its last value (the end-of-sequence token a
// player sends after its last frame), so no value of the pass is missed and none of the next
// one is counted; `finish` ends it by hand (for a source without an end).
#include <cmath>

#include "apex/core/registry.hpp"

namespace apex_nodes {

class SequenceMean : public apex::Node {
 public:
  static inline const apex::InputPort<double> kValue{"value", "one per frame, e.g. RegionScore's f1"};
  static inline const apex::OutputPort<double> kMean{"mean",
                                                     "at the end of a sequence: the mean of its values (0 if it had none)"};
  static inline const apex::OutputPort<int> kCount{"count", "at the end of a sequence: how many values it had"};
  static inline const apex::OutputPort<double> kRunning{
      "running", "each value: the mean of the sequence so far (for the Optimizer's racing)"};
  static apex::Manifest manifest() {
    return apex::Manifest("Averages a value over a sequence; sends mean and count at its end, then starts the next")
        .inCategory("evaluation")
        .keepsState("the sum of the sequence so far: a re-run counts the held frame again")
        .input(kValue)
        .output(kMean)
        .output(kCount)
        .output(kRunning)
        .slot("reset", &SequenceMean::reset, "forgets the values so far: a new sequence starts")
        .slot("finish", &SequenceMean::finish, "ends the sequence now, as its end-of-sequence token does: sends mean and count");
  }
  void process() override {
    const double v = *value_.get();
    if (!std::isfinite(v)) throw std::invalid_argument("value " + std::to_string(v) + " is not a number: not counted");
    sum_ += v;
    ++count_;
    running_.publish(sum_ / count_);
  }
  void endOfSequence() override { finish(); }
  void finish() {
    if (count_ == 0) log(apex::LogLevel::Warn, "the sequence ended without a value: its mean is 0");
    mean_.publish(count_ ? sum_ / count_ : 0.0);
    count_out_.publish(count_);
    reset();
  }
  void reset() {
    sum_ = 0;
    count_ = 0;
  }

 private:
  apex::Input<double> value_{this, kValue};
  apex::Output<double> mean_{this, kMean};
  apex::Output<int> count_out_{this, kCount};
  apex::Output<double> running_{this, kRunning};
  double sum_ = 0;
  int count_ = 0;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::SequenceMean, "apex_nodes/SequenceMean");
