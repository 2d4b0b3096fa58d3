// Buffer: the last N messages as one list, a sliding window (e.g. the last 10 poses for a filter).
#include <deque>

#include "apex/core/registry.hpp"
#include "apex_nodes/flow.hpp"

namespace apex_nodes {
namespace param = apex::param;

class Buffer : public StatefulFlowNode {
 public:
  static inline const apex::InputPort<apex::Any> kIn{"in", "any message"};
  static inline const apex::OutputPort<MessageList> kWindow{
      "window", "the last `size` messages (the same objects), oldest first; with each message that comes"};
  static inline const apex::ParamDecl<int> kSize =
      param::integer("size").range(1, 10000).step(1).init(10).describe("how many messages the window holds");
  static inline const apex::ParamDecl<bool> kFullOnly =
      param::flag("full_only").describe("send Nothing until `size` messages have come (else a shorter list at first)");
  static apex::Manifest manifest() {
    return apex::Manifest("Sends the last `size` messages as one list with each message: a sliding window")
        .inCategory("flow")
        .keepsState("the messages it buffers: a re-run adds the held frame again")
        .input(kIn)
        .output(kWindow)
        .param(kSize)
        .param(kFullOnly)
        .slot("reset", &Buffer::reset, "forgets the messages held; the end of a sequence does too");
  }
  void process() override {
    const auto size = static_cast<std::size_t>(size_.get());
    pushWithin(held_, in_.message(), size);
    if (full_only_.get() && held_.size() < size) return;
    window_.publish(MessageList(held_.begin(), held_.end()));
  }
  void reset() override { held_.clear(); }

 private:
  apex::Input<apex::Any> in_{this, kIn};
  apex::Output<MessageList> window_{this, kWindow};
  apex::Param<int> size_{this, kSize};
  apex::Param<bool> full_only_{this, kFullOnly};
  std::deque<apex::Message> held_;  // the newest `size` messages, oldest first
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::Buffer, "apex_nodes/Buffer");
