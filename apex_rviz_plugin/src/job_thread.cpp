#include "apex_rviz_plugin/job_thread.hpp"

#include <chrono>

namespace apex_rviz_plugin {
namespace {
std::int64_t now() { return std::chrono::steady_clock::now().time_since_epoch().count(); }
}  // namespace

JobThread::JobThread() : state_(std::make_shared<State>()) {
  thread_ = std::thread([s = state_] {  // its own reference: the state lives as long as the thread
    std::unique_lock<std::mutex> lock(s->mutex);
    for (;;) {
      s->cv.wait(lock, [&] { return s->stop || s->retired || !s->jobs.empty(); });
      if (s->stop || s->jobs.empty()) return;  // stopped, or retired with nothing left
      auto job = std::move(s->jobs.front());
      s->jobs.pop_front();
      s->started_ns = now();
      lock.unlock();
      job();
      job = nullptr;  // what it holds goes now, not under the lock
      lock.lock();
      s->started_ns = 0;
    }
  });
}

JobThread::~JobThread() {
  bool busy;
  {
    std::lock_guard<std::mutex> lock(state_->mutex);
    state_->stop = true;
    state_->jobs.clear();
    busy = state_->started_ns != 0;
  }
  state_->cv.notify_all();
  if (busy) {
    thread_.detach();  // a call that may never be answered: it ends on its own, or with the process
  } else {
    thread_.join();
  }
}

void JobThread::post(std::function<void()> job) {
  {
    std::lock_guard<std::mutex> lock(state_->mutex);
    state_->jobs.push_back(std::move(job));
  }
  state_->cv.notify_all();
}

void JobThread::retire() {
  {
    std::lock_guard<std::mutex> lock(state_->mutex);
    state_->retired = true;
  }
  state_->cv.notify_all();
}

bool JobThread::finished() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->retired && state_->jobs.empty() && state_->started_ns == 0;
}

double JobThread::busyFor() const {
  const std::int64_t start = state_->started_ns;
  if (start == 0) return 0;
  return std::chrono::duration<double>(std::chrono::steady_clock::duration(now() - start)).count();
}

}  // namespace apex_rviz_plugin
