#include "edit_requests.hpp"

#include "apex/core/log.hpp"

namespace apex {
namespace detail {

void EditRequests::push(std::weak_ptr<NodeState> node, std::string param, ParamValue value) {
  std::lock_guard<std::mutex> lock(m_);
  if (stopped_) return;
  for (auto& r : queue_)  // asked again before it was applied: the newest value only (bounded queue)
    if (!r.node.owner_before(node) && !node.owner_before(r.node) && r.param == param) {
      r.value = std::move(value);
      return;
    }
  queue_.push_back({std::move(node), std::move(param), std::move(value), nullptr});
  if (!worker_.joinable()) worker_ = std::thread([this] { run(); });
  cv_.notify_one();
}

void EditRequests::describe(std::function<void(GraphSnapshot)> done) {
  std::lock_guard<std::mutex> lock(m_);
  if (stopped_) return;
  queue_.push_back({{}, "", ParamValue(), std::move(done)});
  if (!worker_.joinable()) worker_ = std::thread([this] { run(); });
  cv_.notify_one();
}

bool EditRequests::runAt(std::chrono::steady_clock::time_point due, std::function<void()> task) {
  std::lock_guard<std::mutex> lock(m_);
  if (stopped_ || timed_) return false;
  timed_ = std::move(task);
  due_ = due;
  if (!worker_.joinable()) worker_ = std::thread([this] { run(); });
  cv_.notify_one();
  return true;
}

void EditRequests::stop() {
  std::thread worker;
  {
    std::lock_guard<std::mutex> lock(m_);
    stopped_ = true;
    queue_.clear();
    timed_ = nullptr;
    worker = std::move(worker_);
  }
  cv_.notify_one();
  if (worker.joinable()) worker.join();
}

void EditRequests::unlocked(std::unique_lock<std::mutex>& lock, const char* what, const std::function<void()>& fn) {
  lock.unlock();  // an edit waits for thread groups, whose nodes may push meanwhile
  try {
    fn();
  } catch (const std::exception& e) {  // out of memory, a system error: that request is lost, not the process
    log(LogLevel::Error, "", std::string(what) + " failed: " + e.what());
  }
  lock.lock();
}

void EditRequests::run() {
  std::unique_lock<std::mutex> lock(m_);
  const auto due = [this] { return timed_ && std::chrono::steady_clock::now() >= due_; };
  for (;;) {
    while (!stopped_ && queue_.empty() && !due()) {  // (a task may come while it waits)
      if (timed_) cv_.wait_until(lock, due_);
      else cv_.wait(lock);
    }
    if (stopped_) return;
    if (queue_.empty()) {
      if (!due()) continue;
      auto task = std::move(timed_);
      timed_ = nullptr;
      unlocked(lock, "telling sources of a change downstream", task);
      continue;
    }
    Request r = std::move(queue_.front());
    queue_.pop_front();
    if (r.described) {
      unlocked(lock, "a node's request for the graph's description", [&] { r.described(describe_()); });
      continue;
    }
    auto node = r.node.lock();
    if (!node) continue;
    unlocked(lock, ("a node's request to set its parameter '" + r.param + "'").c_str(), [&] { apply_(node, r.param, r.value); });
    node.reset();
  }
}

}  // namespace detail
}  // namespace apex
