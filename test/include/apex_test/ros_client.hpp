// Calling the runtime's services from rostest gtests: wait for the service,
// call, fail the test with the service's message when asked to.
#pragma once

#include <gtest/gtest.h>
#include <ros/ros.h>

#include <apex/GetGraph.h>
#include <apex/RuntimeStatus.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>

namespace apex_test {

inline std::string service(const std::string& name) { return "/apex/" + name; }

/** Calls a service; ADD_FAILURE if the call itself fails (not if success is false). */
template <class Srv>
typename Srv::Response call(const std::string& name, typename Srv::Request req = {}) {
  Srv srv;
  srv.request = req;
  const std::string full = service(name);
  if (!ros::service::waitForService(full, ros::Duration(60))) ADD_FAILURE() << full << " never appeared";
  if (!ros::service::call(full, srv)) ADD_FAILURE() << "calling " << full << " failed";
  return srv.response;
}

/** The graph as file text: compared before and after a refused edit. */
inline std::string graphText() { return call<apex::GetGraph>("get_graph").yaml; }

/** Waits for the next message on a topic (needs a spinner running); false on timeout. */
template <class Msg>
bool receive(ros::NodeHandle& nh, const std::string& topic, Msg& out, double timeout = 20) {
  std::mutex m;
  std::condition_variable cv;
  bool got = false;
  auto sub = nh.subscribe<Msg>(topic, 1, [&](const typename Msg::ConstPtr& msg) {
    std::lock_guard<std::mutex> l(m);
    out = *msg;
    got = true;
    cv.notify_all();
  });
  std::unique_lock<std::mutex> l(m);
  return cv.wait_for(l, std::chrono::duration<double>(timeout), [&] { return got; });
}

/** The firings of `node` in the next ~status message (0 if it is not listed). */
inline std::uint64_t firingsOf(ros::NodeHandle& nh, const std::string& node) {
  apex::RuntimeStatus status;
  EXPECT_TRUE(receive(nh, "/apex/status", status)) << "no ~status";
  for (const auto& n : status.nodes)
    if (n.name == node) return n.firings;
  return 0;
}

/** Whether `node` keeps firing: a later ~status shows more firings (statuses come every 0.5 s). */
inline bool keepsFiring(ros::NodeHandle& nh, const std::string& node) {
  const auto first = firingsOf(nh, node);
  for (int i = 0; i < 10; ++i)
    if (firingsOf(nh, node) > first) return true;
  return false;
}

/** Counts the messages arriving on a topic (counted on the spinner's threads). */
template <class Msg>
class TopicCounter {
 public:
  TopicCounter(ros::NodeHandle& nh, const std::string& topic)
      : sub_(nh.subscribe<Msg>(topic, 5, [this](const typename Msg::ConstPtr&) {
          std::lock_guard<std::mutex> l(m_);
          ++count_;
          cv_.notify_all();
        })) {}
  long count() {
    std::lock_guard<std::mutex> l(m_);
    return count_;
  }
  /** At least `n` more messages than `since` arrive within `timeout` seconds. */
  bool waitBeyond(long since, long n, double timeout) {
    std::unique_lock<std::mutex> l(m_);
    return cv_.wait_for(l, std::chrono::duration<double>(timeout), [&] { return count_ >= since + n; });
  }
  /** At least `n` more messages arrive within `timeout` seconds. */
  bool flows(long n = 3, double timeout = 20) { return waitBeyond(count(), n, timeout); }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  long count_ = 0;
  ros::Subscriber sub_;  // last: its callback uses the members above
};

/** Waits until `done()` holds, checking every 10 ms, for at most `seconds` (wall time). */
template <class F>
bool waitUntil(F done, double seconds) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
  while (!done()) {
    if (ros::WallTime::now() > end) return false;
    ros::WallDuration(0.01).sleep();
  }
  return true;
}

}  // namespace apex_test
