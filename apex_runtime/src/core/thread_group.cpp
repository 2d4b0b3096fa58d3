#include "thread_group.hpp"

#include <algorithm>

#include "node_state.hpp"

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
  running_ = true;
  started_ = Clock::now();
  thread_ = std::thread([this] { run(); });
}

void ThreadGroup::stop() {
  {
    std::lock_guard<std::mutex> lock(m_);
    if (!thread_.joinable()) return;
    stop_ = true;
    cv_.notify_all();
  }
  thread_.join();
  std::lock_guard<std::mutex> lock(m_);
  waiting_ = false;
  running_ = false;
  state_cv_.notify_all();  // idle waiters: a stopped group has nothing running
}

void ThreadGroup::push(NodeState* node) {
  std::lock_guard<std::mutex> lock(m_);
  if (node->queued) return;
  node->queued = true;
  ready_.push_back(node);
  ++activity_;
  if (waiting_ && pause_requests_ == 0 && canFire()) {
    waiting_ = false;  // one wake-up is enough: later pushes find the thread awake
    wakeups_.fetch_add(1, std::memory_order_relaxed);
    cv_.notify_one();
  }
}

void ThreadGroup::unqueue(NodeState* node) {
  std::lock_guard<std::mutex> lock(m_);
  if (!node->queued) return;
  ready_.erase(std::remove(ready_.begin(), ready_.end(), node), ready_.end());
  node->queued = false;
}

void ThreadGroup::post(Mail mail) {
  std::lock_guard<std::mutex> lock(m_);
  mail_.push_back(std::move(mail));
  ++activity_;
  if (waiting_ && pause_requests_ == 0) {
    waiting_ = false;
    wakeups_.fetch_add(1, std::memory_order_relaxed);
    cv_.notify_one();
  }
}

void ThreadGroup::notifyAt(Clock::time_point when, std::shared_ptr<NodeState> node) {
  std::lock_guard<std::mutex> lock(m_);
  const bool earliest = timers_.empty() || when < timers_.begin()->first;
  timers_.emplace(when, std::move(node));
  if (earliest && waiting_ && pause_requests_ == 0) cv_.notify_one();  // re-arm the wait
}

void ThreadGroup::pause() {
  std::unique_lock<std::mutex> lock(m_);
  ++pause_requests_;
  if (!running_) return;  // not running: always at a boundary
  state_cv_.wait(lock, [this] { return !busy_; });
}

void ThreadGroup::resume() {
  std::lock_guard<std::mutex> lock(m_);
  if (--pause_requests_ == 0 && (canFire() || !mail_.empty())) cv_.notify_one();
}

void ThreadGroup::hold(bool on) {
  std::lock_guard<std::mutex> lock(m_);
  hold_ = on;
  step_budget_ = 0;
  if (!on) cv_.notify_one();
}

void ThreadGroup::beginStep() {
  std::lock_guard<std::mutex> lock(m_);
  step_budget_ = ready_.size();
  cv_.notify_one();
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

GroupStats ThreadGroup::stats() const {
  GroupStats s;
  s.name = name_;
  s.busy_ns = busy_ns_.load(std::memory_order_relaxed);
  s.firings = firings_.load(std::memory_order_relaxed);
  s.wakeups = wakeups_.load(std::memory_order_relaxed);
  std::lock_guard<std::mutex> lock(m_);
  if (running_)
    s.wall_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - started_).count();
  return s;
}

void ThreadGroup::runMail(std::vector<Mail>& batch) {
  for (auto& mail : batch) {
    NodeState& node = *mail.node;
    ThreadGroup* home;
    {
      std::lock_guard<std::mutex> lock(node.group_mutex);  // an edit may move or remove it meanwhile
      if (node.removed) continue;
      home = node.group;
    }
    if (home != this) {  // the node moved to another group: its work follows it
      home->post(std::move(mail));
      continue;
    }
    mail.fn(node);
  }
}

void ThreadGroup::run() {
  tl_current = this;
  std::unique_lock<std::mutex> lock(m_);
  std::vector<Mail> batch;
  while (!stop_) {
    if (pause_requests_ == 0 && !mail_.empty()) {
      batch.swap(mail_);
      busy_ = true;
      lock.unlock();
      runMail(batch);
      batch.clear();  // drops node references outside the lock
      lock.lock();
      busy_ = false;
      continue;
    }
    if (pause_requests_ == 0 && canFire()) {
      NodeState* node = ready_.front();
      ready_.pop_front();
      node->queued = false;
      if (hold_) --step_budget_;
      busy_ = true;
      lock.unlock();
      const auto t0 = Clock::now();
      const bool fired = node->fireIfReady();
      const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t0).count();
      if (fired) node->recordFiring(ns);
      busy_ns_.fetch_add(ns, std::memory_order_relaxed);
      firings_.fetch_add(fired, std::memory_order_relaxed);
      lock.lock();
      busy_ = false;
      continue;
    }
    if (pause_requests_ == 0 && !timers_.empty() && timers_.begin()->first <= Clock::now()) {
      auto node = std::move(timers_.begin()->second);
      timers_.erase(timers_.begin());
      lock.unlock();
      node->notifyNewData();  // pushes onto this or the node's current group
      node.reset();
      lock.lock();
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
