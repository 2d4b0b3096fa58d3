// Accumulate: collects messages until an event, then sends them as one list (e.g. the detections of
// one pass of a bag, or every 100 scans).
#include <deque>
#include <iterator>

#include "apex/core/registry.hpp"
#include "apex_nodes/flow.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Accumulate : public apex::Node {
 public:
  static constexpr std::size_t kMaxHeld = 100000;  // with no count: the oldest go beyond this
  static inline const apex::InputPort<apex::Any> kIn{"in", "any message; Nothing is not collected"};
  static inline const apex::OutputPort<MessageList> kValues{
      "values", "the messages collected (the same objects), oldest first, when a list is sent; Nothing meanwhile"};
  static inline const apex::ParamDecl<int> kCount = param::integer("count").range(0, 100000).step(1).init(0).describe(
      "send the list when it holds this many messages; 0: only at `flush` or the end of a sequence");
  static apex::Manifest manifest() {
    return apex::Manifest(
               "Collects messages until `count` have come, the `flush` slot or the end of a sequence, then sends them as one "
               "list and starts a new one")
        .inCategory("flow")
        .keepsState("its running total: a re-run adds the held frame again")
        .input(kIn)
        .output(kValues)
        .param(kCount)
        .slot("flush", &Accumulate::flush, "sends the messages collected so far (an empty list if none) and starts anew")
        .slot("reset", &Accumulate::reset, "drops the messages collected so far, sending nothing");
  }
  void process() override {
    if (held_.size() == kMaxHeld) {
      if (!warned_) log(apex::LogLevel::Warn, "holds " + std::to_string(kMaxHeld) + " messages: dropping the oldest");
      warned_ = true;
    }
    pushWithin(held_, in_.message(), kMaxHeld);
    if (count_.get() > 0 && held_.size() >= static_cast<std::size_t>(count_.get())) flush();
  }
  /** The list goes out in the token's place (as SequenceMean's mean): the pass's last messages are in it. */
  void endOfSequence() override { flush(); }
  void flush() {
    values_.publish(MessageList(std::make_move_iterator(held_.begin()), std::make_move_iterator(held_.end())));
    reset();
  }
  void reset() {
    held_.clear();
    warned_ = false;
  }

 private:
  apex::Input<apex::Any> in_{this, kIn};
  apex::Output<MessageList> values_{this, kValues};
  apex::Param<int> count_{this, kCount};
  std::deque<apex::Message> held_;  // collected since the last list, oldest first
  bool warned_ = false;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Accumulate, "apex_nodes/Accumulate");
