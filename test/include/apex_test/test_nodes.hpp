// Reusable node types for core tests, with counters a test can wait on.
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "apex/core/graph.hpp"

namespace apex_test {

using namespace apex;
using namespace std::chrono_literals;

constexpr double kWait = 10.0;  // seconds: generous, a passing test never waits this long

/** A driven source: feed(v) queues values; each firing publishes one. Nothing is dropped. */
class Feeder : public Node {
 public:
  static Manifest manifest() { return Manifest("feeds queued ints").output<int>("out").driven(); }
  void feed(int v) {
    bool was_empty;
    {
      std::lock_guard<std::mutex> l(m_);
      was_empty = queue_.empty();
      queue_.push_back(v);
    }
    // Only what makes the queue non-empty wakes it (a firing that leaves more wakes it again):
    // a wake for every value could come after a firing had taken that value already, and the
    // firing it caused, on an empty queue, would send Nothing (seen once under TSan and load).
    if (was_empty) notifyNewData();
  }
  void process() override {
    int v;
    bool more;
    {
      std::lock_guard<std::mutex> l(m_);
      if (queue_.empty()) return;  // sends Nothing
      v = queue_.front();
      queue_.pop_front();
      more = !queue_.empty();
    }
    publish("out", v);
    if (more) notifyNewData();
  }

 private:
  std::mutex m_;
  std::deque<int> queue_;
};

/** A free-running source: 0, 1, 2, ... as fast as its receivers read. */
class Ticker : public Node {
 public:
  static Manifest manifest() { return Manifest("counts up").output<int>("out"); }
  void process() override { publish("out", n_++); }

 private:
  int n_ = 0;
};

/** Passes any message on. */
class Relay : public Node {
 public:
  static Manifest manifest() { return Manifest("passes anything").input<Any>("in").output<Any>("out"); }
  void process() override { publishMessage("out", inputMessage("in")); }
};

/** Adds `gain` (an interactive-capable parameter) times the input. */
class Gain : public Node {
 public:
  static Manifest manifest() {
    return Manifest("multiplies by gain")
        .input<int>("in")
        .output<int>("out")
        .param(param::range("gain", -100, 100, 1, 1).describe("factor"));
  }
  void process() override { publish("out", *input<int>("in") * param<int>("gain")); }
};

/** Sums a and, if present, the optional b. */
class OptionalSum : public Node {
 public:
  static Manifest manifest() { return Manifest("a + b?").input<int>("a").optionalInput<int>("b").output<int>("sum"); }
  void process() override {
    int s = *input<int>("a");
    if (hasInput("b")) s += *input<int>("b");
    publish("sum", s);
  }
};

/** Throws when the input equals `throw_on`, else passes it on; its slot `start` throws while
 *  `throw_on` is negative, as a run started without its settings does. */
class Thrower : public Node {
 public:
  static Manifest manifest() {
    return Manifest("throws on one value, or on all")
        .input<int>("in")
        .output<int>("out")
        .slot("start", &Thrower::start, "throws while throw_on is negative")
        .param(param::integer("throw_on", -1))
        .param(param::boolean("throw_always", false));
  }
  void start() {
    if (param<int>("throw_on") < 0) throw std::runtime_error("give throw_on first");
  }
  void process() override {
    const int v = *input<int>("in");
    if (v == param<int>("throw_on") || param<bool>("throw_always")) throw std::runtime_error("bad value " + std::to_string(v));
    publish("out", v);
  }
};

/** Counts events on its own slot and fires its own trigger every `every` firings. */
class Counter : public Node {
 public:
  static Manifest manifest() {
    return Manifest("counts firings")
        .input<Any>("in")
        .slot("reset", &Counter::reset, "sets the count to zero")
        .trigger("every_n", "fires every `every` inputs")
        .param(param::integer("every", 3));
  }
  void process() override {
    if (++count % param<int>("every") == 0) trigger("every_n");
  }
  void reset() {
    count = 0;
    ++resets;
  }
  std::atomic<int> count{0}, resets{0};
};

/** Records every message it receives (including Nothing); tests wait on it. */
class Collector : public Node {
 public:
  static Manifest manifest() { return Manifest("records messages, Nothing too").optionalInput<Any>("in"); }
  void process() override {
    std::lock_guard<std::mutex> l(m_);
    got_.push_back(inputMessage("in"));
    cv_.notify_all();
  }
  bool waitFor(std::size_t n, double timeout = kWait) {
    std::unique_lock<std::mutex> l(m_);
    return cv_.wait_for(l, std::chrono::duration<double>(timeout), [&] { return got_.size() >= n; });
  }
  std::vector<Message> messages() {
    std::lock_guard<std::mutex> l(m_);
    return got_;
  }
  /** The ints received; Nothing as -999. */
  std::vector<int> ints() {
    std::vector<int> out;
    for (auto& m : messages()) out.push_back(m.isNothing() ? -999 : *m.as<int>());
    return out;
  }
  std::size_t size() {
    std::lock_guard<std::mutex> l(m_);
    return got_.size();
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  std::vector<Message> got_;
};

/** A driven source playing 0..frames-1 on `restart`, then the end of the sequence (at once after
 *  `end_pass`, as BagReader's). */
class Sequence : public Node {
 public:
  static Manifest manifest() {
    return Manifest("plays a short sequence")
        .output<int>("out")
        .slot("restart", &Sequence::restart)
        .slot("end_pass", &Sequence::endPass)
        .trigger("finished")
        .param(param::integer("frames", 3))
        .driven();
  }
  void restart() {
    next_ = 0;
    notifyNewData();
  }
  void endPass() {
    if (next_ < 0) return;
    next_ = param<int>("frames");
    notifyNewData();
  }
  void process() override {
    if (next_ < 0) return;
    if (next_ >= param<int>("frames")) {
      next_ = -1;
      endSequence();
      trigger("finished");
      return;
    }
    publish("out", next_++);
    notifyNewData();
  }

 private:
  int next_ = -1;
};

/** A registry with every test type. */
inline NodeRegistry testRegistry() {
  NodeRegistry r;
  EXPECT_TRUE(r.add<Feeder>("test/Feeder"));
  EXPECT_TRUE(r.add<Ticker>("test/Ticker"));
  EXPECT_TRUE(r.add<Relay>("test/Relay"));
  EXPECT_TRUE(r.add<Gain>("test/Gain"));
  EXPECT_TRUE(r.add<OptionalSum>("test/OptionalSum"));
  EXPECT_TRUE(r.add<Thrower>("test/Thrower"));
  EXPECT_TRUE(r.add<Counter>("test/Counter"));
  EXPECT_TRUE(r.add<Collector>("test/Collector"));
  EXPECT_TRUE(r.add<Sequence>("test/Sequence"));
  return r;
}

template <class T>
T* object(Graph& g, const std::string& name) {
  return dynamic_cast<T*>(g.nodeObject(name));
}

/** Waits until `done()` holds, checking every millisecond, for at most `timeout` seconds. */
template <class F>
bool waitUntil(F done, double timeout = kWait) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  while (!done()) {
    if (std::chrono::steady_clock::now() >= until) return false;
    std::this_thread::sleep_for(1ms);
  }
  return true;
}

/** Adds a node and fails the test if that is refused. */
inline std::string add(Graph& g, const std::string& type, const std::string& name, const std::string& group = "") {
  auto r = g.addNode(type, name, group);
  EXPECT_TRUE(r) << r.message();
  return r ? r.value() : std::string();
}

inline void link(Graph& g, const std::string& a, const std::string& ap, const std::string& b, const std::string& bp) {
  auto st = g.connect(a, ap, b, bp);
  EXPECT_TRUE(st) << st.message();
}

}  // namespace apex_test
