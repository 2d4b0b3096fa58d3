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

void EditRequests::stop() {
  std::thread worker;
  {
    std::lock_guard<std::mutex> lock(m_);
    stopped_ = true;
    queue_.clear();
    worker = std::move(worker_);
  }
  cv_.notify_one();
  if (worker.joinable()) worker.join();
}

void EditRequests::run() {
  std::unique_lock<std::mutex> lock(m_);
  for (;;) {
    cv_.wait(lock, [this] { return stopped_ || !queue_.empty(); });
    if (stopped_) return;
    Request r = std::move(queue_.front());
    queue_.pop_front();
    if (r.described) {
      lock.unlock();
      try {
        r.described(describe_());
      } catch (const std::exception& e) {
        log(LogLevel::Error, "", std::string("a node's request for the graph's description failed: ") + e.what());
      }
      lock.lock();
      continue;
    }
    auto node = r.node.lock();
    if (!node) continue;
    lock.unlock();  // the edit waits for thread groups, whose nodes may push meanwhile
    try {
      apply_(node, r.param, r.value);
    } catch (const std::exception& e) {  // out of memory, a system error: that request is lost, not the process
      log(LogLevel::Error, "", "a node's request to set its parameter '" + r.param + "' failed: " + e.what());
    }
    node.reset();
    lock.lock();
  }
}

}  // namespace detail
}  // namespace apex
