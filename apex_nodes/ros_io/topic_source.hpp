// The base of the subscriber nodes: a driven source that sends the newest
// message of a topic (a busy graph drops frames instead of queueing them).
// With `hold` it keeps the message it sent last, ignores new ones, and sends
// that one again after any change downstream: tuning on a live camera's frame.
#pragma once

#include <boost/shared_ptr.hpp>

#include <atomic>
#include <cstdint>
#include <mutex>

#include "apex/core/node.hpp"
#include "apex/core/param.hpp"
#include "apex/core/ports.hpp"

namespace apex_nodes {

template <class Msg>
class TopicSource : public apex::Node {
 public:
  using MsgPtr = boost::shared_ptr<const Msg>;

  /** roscpp's queue per subscription: a few, so that a moment when every spinner thread is busy
   *  does not drop messages unseen in roscpp; they come one after another once it passes, and
   *  received() keeps the newest and counts the others as dropped (NodeStats::dropped). */
  static constexpr std::uint32_t kQueue = 4;

  /** The parameter every subscriber declares. */
  /** (A function, not a constant: a static member of a class template may be initialised after
   *  the registration lines that read it.) */
  static apex::ParamDecl<bool> holdParam() {
    return apex::param::flag("hold").describe(
        "keep the last message, ignore new ones, and send it again after any change downstream");
  }

  void setup() override { subscribe(); }
  void parameterChanged(const std::string& name) override {
    if (name != "hold") return subscribe();
    holding_ = hold_.get();
    if (!holding_) notifyNewData();  // back to live: the newest message
  }
  void downstreamChanged() override {
    if (!holding_ || !sent_) return;
    resend_ = true;
    notifyNewData();
  }
  void process() override {
    MsgPtr msg;
    if (holding_) {
      if (!resend_) return;  // held: new messages wait
      resend_ = false;
      msg = sent_;
    } else {
      std::lock_guard<std::mutex> lock(m_);
      std::swap(msg, latest_);
    }
    if (!msg) return;
    sent_ = msg;
    send(msg);
  }

 protected:
  /** (Re)subscribes with the current parameters; the callback calls received(). */
  virtual void subscribe() = 0;
  /** Converts and publishes one message (on process()'s thread). */
  virtual void send(const MsgPtr& msg) = 0;
  /** For the subscription's callback, on a ROS thread. */
  void received(const MsgPtr& msg) {
    bool lost;
    {
      std::lock_guard<std::mutex> lock(m_);
      lost = latest_ != nullptr && !holding_;  // the graph had not taken the last one: it is dropped
      latest_ = msg;
    }
    if (lost) countDropped();
    if (!holding_) notifyNewData();
  }

 private:
  apex::Param<bool> hold_{this, holdParam()};  // declared by every subclass: holdParam()
  std::mutex m_;
  MsgPtr latest_;  // m_: the newest from the callback
  MsgPtr sent_;  // process() only: the last one sent (held)
  bool resend_ = false;  // process() only
  std::atomic<bool> holding_{false};  // read by the callback
};

}  // namespace apex_nodes
