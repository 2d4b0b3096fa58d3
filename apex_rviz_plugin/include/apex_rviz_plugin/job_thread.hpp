// A thread that runs jobs (service calls) in order, off the GUI thread. A call
// to a runtime that hangs must not hang the panel: a job thread that is busy
// when it is destroyed is left to finish on its own, and a retired one (the
// runtime of a namespace left behind) runs what it was given while a new one
// serves the next runtime.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

namespace apex_rviz_plugin {

/** @brief Runs jobs in order on one thread of its own. */
class JobThread {
 public:
  JobThread();
  /** @brief Drops the jobs not started; waits for the running one only if it is not
   *  stuck: a job still running is left to end on its own (its thread detached). */
  ~JobThread();
  void post(std::function<void()> job);
  /** @brief Runs the jobs posted so far, then the thread ends (nothing more is taken). */
  void retire();
  /** @brief Retired, and done with all it was given (its thread has ended or is ending). */
  bool finished() const;
  /** @brief Seconds the running job has taken so far; 0 when idle. */
  double busyFor() const;

 private:
  struct State {  // shared with the thread: it may outlive this object
    std::mutex mutex;
    std::condition_variable cv;
    std::deque<std::function<void()>> jobs;
    bool stop = false, retired = false;
    std::atomic<std::int64_t> started_ns{0};  // steady clock, of the running job; 0 when idle
  };
  std::shared_ptr<State> state_;
  std::thread thread_;
};

}  // namespace apex_rviz_plugin
