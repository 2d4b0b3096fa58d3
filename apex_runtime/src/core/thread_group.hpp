// One scheduler thread with a ready queue and a mailbox.
// Ownership: the group's mutex guards the queue, the mailbox, the pause and
// hold state and every NodeState queue mark (markQueued) of nodes in this group. A node's
// own state is only touched by this thread, or by an editor while this group
// is paused (see graph.cpp). `inline_next_` and `inline_later_` belong to the thread
// alone: a node that one of its firings made ready runs next without a trip through
// the queue (taskflow's executor does the same), and one made ready earlier in that
// firing waits in `inline_later_` until the chain ends (no lock: a source freed by
// the first relay of a chain runs again after the chain, as from the queue). Both
// are back in the queue before the thread leaves runFirings, so an editor never
// sees them.
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <map>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <set>
#include <thread>
#include <vector>

#include "apex/core/description.hpp"
#include "trace_ring.hpp"

namespace apex {
namespace detail {

class NodeState;

/** An event, parameter value or other work for one node, run on its group's thread. */
struct Mail {
  std::shared_ptr<NodeState> node;
  std::function<void(NodeState&)> fn;
};

class ThreadGroup {
 public:
  ThreadGroup(std::string name, const void* owner) : name_(std::move(name)), owner_(owner) {}
  ~ThreadGroup() { stop(); }

  const std::string& name() const { return name_; }
  /** @brief The graph this group belongs to. */
  const void* owner() const { return owner_; }
  /** @brief The group whose thread is calling, or nullptr on any other thread. */
  static const ThreadGroup* current();
  void start();
  void stop();
  /** @brief Nothing queued, posted or timed here: it may go (no node is in it; call it paused). */
  bool unused() const;

  /** @brief A node became ready; wakes the thread only if it sleeps. */
  void push(NodeState* node);
  /** @brief From a firing on this group's thread: `node` (of this group) became ready and runs next. */
  void runNext(NodeState* node) {  // inline: every hop within a group passes here
    if (inline_next_) inline_later_.push_back(inline_next_);  // the last one made ready runs next
    inline_next_ = node;
  }
  /** @brief Removes a node from the ready queue (the group must be paused). */
  void unqueue(NodeState* node);
  /** @brief Work for a node, run between firings. */
  void post(Mail mail);
  /** @brief Calls the node's notifyNewData() at `when` (a timer; pending timers do not keep the group busy). */
  void notifyAt(std::chrono::steady_clock::time_point when, std::shared_ptr<NodeState> node);
  /** @brief Runs `mail` at `when` (a timer, as above) on the node's group: this one, or the one it
   *  moved to since. */
  void at(std::chrono::steady_clock::time_point when, Mail mail);

  /** @brief Returns once the thread is parked at a firing boundary; counted, so
   *  several editors may pause at once. Cheap when the thread is idle. */
  void pause();
  void resume();

  /** @brief Graph-wide pause: no firing (mail still runs) until released. */
  void hold(bool on);
  /** @brief While held: allow the nodes ready now to fire once each. */
  void beginStep();
  void waitStep();
  /** @brief While held: each source may fire once, every other node fires freely (a frame
   *  goes all the way through); ends with endFrameStep(). Idle means nothing more can fire. */
  void beginFrameStep();
  void endFrameStep();

  /** @brief Waits until nothing is ready, running or posted, or the group is stopped; false on timeout. */
  bool waitIdle(std::chrono::steady_clock::time_point deadline);
  /** @brief Counts pushes and posts: unchanged between two idle checks means no work moved. */
  std::uint64_t activity() const;
  GroupStats stats() const;
  /** @brief The frame trace: while on, each firing here goes into a ring of `capacity` firings,
   *  made when first turned on and kept when turned off (its firings can still be read). Call
   *  under the graph's edit lock. */
  void setTracing(bool on, std::size_t capacity);
  /** @brief Its trace ring; nullptr if it never traced. Under the graph's edit lock. */
  const TraceRing* traceRing() const { return ring_.get(); }

 private:
  void run();
  void runMail(std::vector<Mail>& batch);
  /** Fires `node`, then the successors it made ready here, while nothing else needs the thread. */
  void runFirings(NodeState* node);
  void queueLocked(NodeState* node);
  /** Puts `node` and everything in inline_later_ in the queue (firings end: something else
   *  needs the thread). */
  void queueInline(NodeState* node);
  /** Something besides the inline chain needs the thread: a pause, mail, a hold, stop, or a
   *  node another thread made ready (often one that frees a sender in another group: it must
   *  not wait behind this group's whole chain, or two groups stop overlapping). Under m_. */
  void updateAttention() {
    attention_.store(pause_requests_ > 0 || !mail_.empty() || hold_ || stop_ || queued_from_outside_ > 0,
                     std::memory_order_relaxed);
  }
  bool canFire() const { return firable() >= 0; }
  /** Whether the mail runs before the next firing: always when some of it was posted before
   *  that node was queued (a value or an event sent ahead of its data stays ahead: the tuning
   *  loop relies on it); mail posted since may wait until the nodes queued before it have fired,
   *  so that mail arriving faster than it runs cannot keep this group's nodes from ever firing. Under m_. */
  bool mailFirst() const;
  /** The position in ready_ of the next node allowed to fire, -1 if none. */
  int firable() const;
  // a stopped group counts as idle: nothing will run there until it starts again
  bool idleLocked() const { return !running_ || (mail_.empty() && !canFire() && !busy_ && waiting_); }

  const std::string name_;
  const void* const owner_;
  mutable std::mutex m_;
  std::condition_variable cv_;  // wakes the thread
  std::condition_variable state_cv_;  // the thread parked, stepped or went idle
  std::deque<NodeState*> ready_;
  std::vector<Mail> mail_;
  std::multimap<std::chrono::steady_clock::time_point, Mail> timers_;
  bool waiting_ = false;  // the thread waits on cv_ (at a firing boundary)
  bool busy_ = false;  // the thread runs a firing or mail
  bool stop_ = false;
  bool running_ = false;  // the thread runs (false again once joined)
  int pause_requests_ = 0;
  bool hold_ = false;
  std::size_t step_budget_ = 0;
  bool frame_step_ = false;
  std::set<const NodeState*> stepped_sources_;  // fired in this frame step
  std::uint64_t activity_ = 0;
  std::thread thread_;
  std::atomic<bool> attention_{false};
  NodeState* inline_next_ = nullptr;  // made ready by that firing, runs next (thread only)
  std::deque<NodeState*> inline_later_;  // made ready before it, run after the chain (thread only)
  int queued_from_outside_ = 0;  // nodes in ready_ that push() put there (m_)
  std::uint64_t posted_ = 0;  // mail posted here so far (m_)
  std::uint64_t taken_ = 0;  // ... of which run() has taken into a batch (m_)
  static constexpr int kInlineRun = 256;  // then the queue gets a turn
  static constexpr std::int64_t kInlineTicks = 1 << 18;  // ~65-260 µs: then timers get a turn

  std::atomic<std::uint64_t> firings_{0}, wakeups_{0};
  std::atomic<std::int64_t> busy_t_{0};  // ticks (ticks.hpp)
  std::unique_ptr<TraceRing> ring_;  // the graph's edit lock
  std::atomic<TraceRing*> tracing_{nullptr};  // ring_ while tracing: read once per runFirings
  std::chrono::steady_clock::time_point started_{};
};

}  // namespace detail
}  // namespace apex
