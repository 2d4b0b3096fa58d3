// Delay: any message as it came N frames ago, e.g. an image to subtract from this one (frame differencing).
#include <deque>

#include "apex/core/registry.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Delay : public apex::Node {
 public:
  static inline const apex::InputPort<apex::Any> kIn{"in", "any message"};
  static inline const apex::OutputPort<apex::Any> kOut{
      "out", "the message of `frames` messages ago (the same object); Nothing until then"};
  static inline const apex::ParamDecl<int> kFrames =
      param::integer("frames").range(1, 100).step(1).init(1).describe("how many messages ago");
  static apex::Manifest manifest() {
    return apex::Manifest("Sends each message again `frames` messages later: with this frame, the one of N frames ago")
        .inCategory("flow")
        .keepsState("the messages it delays: a re-run pushes the held frame in again")
        .input(kIn)
        .output(kOut)
        .param(kFrames)
        .slot("reset", &Delay::reset, "forgets the messages held: Nothing until `frames` more have come");
  }
  void process() override {
    held_.push_back(in_.message());
    const auto n = static_cast<std::size_t>(frames_.get());
    while (held_.size() > n + 1) held_.pop_front();  // `frames` was lowered: the newest stay
    if (held_.size() == n + 1) {
      out_.publishMessage(held_.front());
      held_.pop_front();
    }
  }
  /** A new pass of a sequence does not get the last pass's frames. */
  void endOfSequence() override {
    reset();
    endSequence();
  }
  void reset() { held_.clear(); }

 private:
  apex::Input<apex::Any> in_{this, kIn};
  apex::Output<apex::Any> out_{this, kOut};
  apex::Param<int> frames_{this, kFrames};
  std::deque<apex::Message> held_;  // the last `frames` messages, oldest first
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Delay, "apex_nodes/Delay");
