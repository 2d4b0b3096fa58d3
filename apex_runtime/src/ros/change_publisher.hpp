// ~graph and what follows it (the parameter mirror, dynamic_reconfigure, diagnostics) published
// off the caller's thread: a service call that edits the graph wakes this and answers at once.
// Describing and publishing a big graph costs O(graph) (tens of ms at 5,000 nodes); done in each
// call, it made every edit cost that. One thread publishes the newest revision; the edits of a
// burst that come while it publishes, or in a rest after it four times as long, are in the next
// one: at most a fifth of a core and of the edit lock's time goes to publishing, however big the
// graph and fast the edits (a single edit is published at once; at 5,000 nodes a burst's are
// seen every ~0.2 s).
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

namespace apex {
namespace ros_host {

class ChangePublisher {
 public:
  /** `publish`: publishes the graph if it changed (called on this class's thread only). */
  explicit ChangePublisher(std::function<void()> publish);
  ~ChangePublisher() { stop(); }
  ChangePublisher(const ChangePublisher&) = delete;
  ChangePublisher& operator=(const ChangePublisher&) = delete;

  /** Something may have changed: publish soon. Returns at once; any thread. */
  void wake();
  /** Publishes nothing more: waits for a publication under way. Idempotent. */
  void stop();

 private:
  void run();
  static constexpr int kRest = 5;  // a publication and its rest: five times its length

  std::function<void()> publish_;
  std::mutex m_;
  std::condition_variable cv_;
  bool pending_ = false, stopped_ = false;
  std::thread thread_;
};

}  // namespace ros_host
}  // namespace apex
