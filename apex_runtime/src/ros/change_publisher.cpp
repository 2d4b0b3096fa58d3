#include "change_publisher.hpp"

#include <ros/console.h>

#include <chrono>
#include <exception>

namespace apex {
namespace ros_host {

ChangePublisher::ChangePublisher(std::function<void()> publish) : publish_(std::move(publish)) {
  thread_ = std::thread([this] { run(); });
}

void ChangePublisher::wake() {
  {
    std::lock_guard<std::mutex> lock(m_);
    pending_ = true;
  }
  cv_.notify_one();
}

void ChangePublisher::stop() {
  {
    std::lock_guard<std::mutex> lock(m_);
    stopped_ = true;
  }
  cv_.notify_one();
  if (thread_.joinable()) thread_.join();
}

void ChangePublisher::run() {
  std::unique_lock<std::mutex> lock(m_);
  for (;;) {
    cv_.wait(lock, [this] { return stopped_ || pending_; });
    if (stopped_) return;
    pending_ = false;  // a wake from now on publishes once more
    lock.unlock();
    const auto start = std::chrono::steady_clock::now();
    try {
      publish_();
    } catch (const std::exception& e) {  // the next change tries again
      ROS_ERROR_STREAM_NAMED("apex", "publishing the graph failed: " << e.what());
    }
    const auto took = std::chrono::steady_clock::now() - start;
    lock.lock();
    cv_.wait_until(lock, start + kRest * took, [this] { return stopped_; });
  }
}

}  // namespace ros_host
}  // namespace apex
