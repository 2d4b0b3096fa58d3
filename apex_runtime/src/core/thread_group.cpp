#include "thread_group.hpp"

#include <algorithm>

#include "node_state.hpp"
#include "ticks.hpp"

namespace apex {
namespace detail {

using Clock = std::chrono::steady_clock;

namespace {
thread_local const ThreadGroup* tl_current = nullptr;
}

const ThreadGroup* ThreadGroup::current() { return tl_current; }

void ThreadGroup::start() {
  std::lock_guard<std::mutex> lock(m_);
  if (thread_.joinable()) return;
  stop_ = false;
  updateAttention();
  running_ = true;
  started_ = Clock::now();
  thread_ = std::thread([this] { run(); });
}

bool ThreadGroup::unused() const {
  std::lock_guard<std::mutex> lock(m_);
  return ready_.empty() && mail_.empty() && timers_.empty();
}

void ThreadGroup::stop() {
  {
    std::lock_guard<std::mutex> lock(m_);
    if (!thread_.joinable()) return;
    stop_ = true;
    updateAttention();
    cv_.notify_all();
  }
  thread_.join();
  std::lock_guard<std::mutex> lock(m_);
  waiting_ = false;
  running_ = false;
  state_cv_.notify_all();  // idle waiters: a stopped group has nothing running
}

void ThreadGroup::queueLocked(NodeState* node) {
  if (!node->markQueued(posted_)) return;
  ready_.push_back(node);
  ++activity_;
}

void ThreadGroup::queueInline(NodeState* node) {
  std::lock_guard<std::mutex> lock(m_);
  if (node) queueLocked(node);  // behind the others: a busy chain must not starve them
  for (NodeState* n : inline_later_) queueLocked(n);
  inline_later_.clear();
}

void ThreadGroup::push(NodeState* node) {
  std::lock_guard<std::mutex> lock(m_);
  if (node->queued()) return;
  queueLocked(node);
  node->markFromOutside();
  ++queued_from_outside_;
  updateAttention();
  if (waiting_ && pause_requests_ == 0 && canFire()) {
    waiting_ = false;  // one wake-up is enough: later pushes find the thread awake
    wakeups_.fetch_add(1, std::memory_order_relaxed);
    cv_.notify_one();
  }
}

void ThreadGroup::unqueue(NodeState* node) {
  std::lock_guard<std::mutex> lock(m_);
  if (!node->queued()) return;
  ready_.erase(std::remove(ready_.begin(), ready_.end(), node), ready_.end());
  if (node->clearQueued()) {
    --queued_from_outside_;
    updateAttention();
  }
}

void ThreadGroup::post(Mail mail) {
  std::lock_guard<std::mutex> lock(m_);
  mail_.push_back(std::move(mail));
  ++posted_;
  updateAttention();
  ++activity_;
  if (waiting_ && pause_requests_ == 0) {
    waiting_ = false;
    wakeups_.fetch_add(1, std::memory_order_relaxed);
    cv_.notify_one();
  }
}

void ThreadGroup::notifyAt(Clock::time_point when, std::shared_ptr<NodeState> node) {
  at(when, Mail{std::move(node), [](NodeState& n) { n.notifyNewData(); }});  // pushes onto the node's current group
}

void ThreadGroup::at(Clock::time_point when, Mail mail) {
  std::lock_guard<std::mutex> lock(m_);
  const bool earliest = timers_.empty() || when < timers_.begin()->first;
  timers_.emplace(when, std::move(mail));
  if (earliest && waiting_ && pause_requests_ == 0) cv_.notify_one();  // re-arm the wait
}

void ThreadGroup::pause() {
  std::unique_lock<std::mutex> lock(m_);
  ++pause_requests_;
  updateAttention();
  if (!running_) return;  // not running: always at a boundary
  state_cv_.wait(lock, [this] { return !busy_; });
}

void ThreadGroup::resume() {
  std::lock_guard<std::mutex> lock(m_);
  --pause_requests_;
  updateAttention();
  if (pause_requests_ == 0 && (canFire() || !mail_.empty())) cv_.notify_one();
}

void ThreadGroup::hold(bool on) {
  std::lock_guard<std::mutex> lock(m_);
  hold_ = on;
  updateAttention();
  step_budget_ = 0;
  if (!on) cv_.notify_one();
}

void ThreadGroup::beginStep() {
  std::lock_guard<std::mutex> lock(m_);
  step_budget_ = ready_.size();
  cv_.notify_one();
}

void ThreadGroup::beginFrameStep() {
  std::lock_guard<std::mutex> lock(m_);
  frame_step_ = true;
  stepped_sources_.clear();
  cv_.notify_one();
}

void ThreadGroup::endFrameStep() {
  std::lock_guard<std::mutex> lock(m_);
  frame_step_ = false;
  stepped_sources_.clear();
}

int ThreadGroup::firable() const {
  if (ready_.empty()) return -1;
  if (!hold_ || step_budget_ > 0) return 0;
  if (!frame_step_) return -1;
  // Structure (isSource) changes only in edits, which pause this group: stable here.
  for (std::size_t i = 0; i < ready_.size(); ++i)
    if (!ready_[i]->isSource() || !stepped_sources_.count(ready_[i])) return static_cast<int>(i);
  return -1;
}

bool ThreadGroup::mailFirst() const {
  const int next = firable();
  return next < 0 || ready_[next]->readyMark() > taken_;
}

void ThreadGroup::waitStep() {
  std::unique_lock<std::mutex> lock(m_);
  if (!running_) return;
  state_cv_.wait(lock, [this] { return (step_budget_ == 0 || ready_.empty()) && !busy_; });
  step_budget_ = 0;
}

bool ThreadGroup::waitIdle(Clock::time_point deadline) {
  std::unique_lock<std::mutex> lock(m_);
  return state_cv_.wait_until(lock, deadline, [this] { return idleLocked(); });
}

std::uint64_t ThreadGroup::activity() const {
  std::lock_guard<std::mutex> lock(m_);
  return activity_;
}

void ThreadGroup::setTracing(bool on, std::size_t capacity) {
  if (on && !ring_) ring_ = std::make_unique<TraceRing>(capacity);
  tracing_.store(on ? ring_.get() : nullptr, std::memory_order_release);
}

GroupStats ThreadGroup::stats() const {
  GroupStats s;
  s.name = name_;
  s.busy_ns = ticksToNs(busy_t_.load(std::memory_order_relaxed));
  s.firings = firings_.load(std::memory_order_relaxed);
  s.wakeups = wakeups_.load(std::memory_order_relaxed);
  std::lock_guard<std::mutex> lock(m_);
  if (running_) s.wall_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - started_).count();
  return s;
}

void ThreadGroup::runMail(std::vector<Mail>& batch) {
  for (auto& mail : batch) {
    NodeState& node = *mail.node;
    ThreadGroup* home = node.homeGroup();  // an edit may move or remove it meanwhile
    if (!home) continue;
    if (home != this) {  // the node moved to another group: its work follows it
      home->post(std::move(mail));
      continue;
    }
    mail.fn(node);
  }
}

void ThreadGroup::runFirings(NodeState* node) {
  // Clock reads cost ~10 ns here, a quarter of a trivial hop: a firing is timed only when its
  // node asks (NodeState::timeNext), and starts at the newest read if nothing ran since.
  const std::int64_t start = ticks();
  std::int64_t now = start;  // the newest clock read
  bool fresh = true;  // nothing ran since `now`
  const auto relaxed = std::memory_order_relaxed;
  std::uint64_t fired = 0;
  TraceRing* const ring = tracing_.load(std::memory_order_acquire);  // tracing: every firing timed and kept
  for (int run = 0; node; ++run) {
    const bool timed = ring || node->timeNext();
    if (timed && !fresh) now = ticks();
    const std::int64_t t0 = now;
    const bool ok = node->fireIfReady();
    if (timed) now = ticks();
    fresh = timed;
    if (ok) {
      node->recordFiring(timed, now - t0, now);
      if (ring) ring->write({node->seq() | (node->startsFrame() ? TraceRecord::kStartsFrame : 0), t0, now, node->frame()});
      ++fired;
    }
    node = inline_next_;
    inline_next_ = nullptr;
    if (!node && !inline_later_.empty()) {  // the chain ended: the oldest one made ready in it
      node = inline_later_.front();
      inline_later_.pop_front();
      // a slow chain returns to run() after each pass, as through the queue: due timers first
      if (now - start >= kInlineTicks) run = kInlineRun;
    }
    if (node && (run >= kInlineRun || attention_.load(relaxed))) {
      queueInline(node);
      node = nullptr;
    }
  }
  const std::int64_t end = fresh ? now : ticks();
  // one writer: no read-modify-write
  firings_.store(firings_.load(relaxed) + fired, relaxed);
  busy_t_.store(busy_t_.load(relaxed) + (end - start), relaxed);
}

void ThreadGroup::run() {
  tl_current = this;
  std::unique_lock<std::mutex> lock(m_);
  std::vector<Mail> batch;
  while (!stop_) {
    if (pause_requests_ == 0 && !mail_.empty() && mailFirst()) {
      batch.swap(mail_);
      taken_ = posted_;
      updateAttention();
      busy_ = true;
      lock.unlock();
      runMail(batch);
      batch.clear();  // drops node references outside the lock
      lock.lock();
      busy_ = false;
      continue;
    }
    // Due timers before firings: a group kept busy by a free-running source must not starve them.
    if (pause_requests_ == 0 && !timers_.empty() && timers_.begin()->first <= Clock::now()) {
      batch.push_back(std::move(timers_.begin()->second));
      timers_.erase(timers_.begin());
      busy_ = true;  // an edit's pause() waits for it, as for any mail (found by ThreadSanitizer)
      lock.unlock();
      runMail(batch);  // like mail: not for a removed node, and on the node's group if it moved since
      batch.clear();  // drops the node reference outside the lock
      lock.lock();
      busy_ = false;
      continue;
    }
    const int next = pause_requests_ == 0 ? firable() : -1;
    if (next >= 0) {
      NodeState* node = ready_[next];
      ready_.erase(ready_.begin() + next);
      const bool from_outside = node->clearQueued();
      if (hold_ && step_budget_ > 0) --step_budget_;
      if (hold_ && frame_step_ && node->isSource()) stepped_sources_.insert(node);
      if (from_outside) {
        --queued_from_outside_;
        updateAttention();
      }
      busy_ = true;
      lock.unlock();
      runFirings(node);
      lock.lock();
      busy_ = false;
      continue;
    }
    waiting_ = true;
    state_cv_.notify_all();  // editors waiting to pause, steppers, idle waiters
    if (timers_.empty()) {
      cv_.wait(lock);
    } else {
      cv_.wait_until(lock, timers_.begin()->first);
    }
    waiting_ = false;
  }
  state_cv_.notify_all();
}

}  // namespace detail
}  // namespace apex
