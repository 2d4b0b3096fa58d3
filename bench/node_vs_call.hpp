// A node type alone against the library call it stands for (OpenCV, PCL), on the same inputs,
// interleaved: what a node adds to its call (input checks, parameter reads, its output buffer,
// taking and delivering messages). The one implementation of that measurement and of its table
// row; apex_bench_images and apex_bench_clouds each bring their cases.
#pragma once

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "apex/core/graph.hpp"
#include "plugin_registry.hpp"
#include "spread.hpp"

#include <cctype>
#include <cstdio>
#include <sched.h>

namespace apex_bench {

using Params = std::vector<std::pair<std::string, std::string>>;

/** The bench's registry: the plugin types and the feeds and sinks below (made on first use). */
inline apex::NodeRegistry& benchRegistry() {
  return pluginRegistry([](apex::NodeRegistry&) {});
}

/** Sends one prepared message per output ("o0", "o1", ...) once per notifyNewData: a node
 *  with several inputs gets them all in the same firing. */
class Feed : public apex::Node {
 public:
  void process() override {
    for (std::size_t i = 0; i < next.size(); ++i) publishMessage("o" + std::to_string(i), next[i]);
  }
  std::vector<apex::Message> next;
};

/** A type id's name part from port type names: letters, digits and '_' only ('package/Name'). */
inline std::string idPart(const std::string& type_name) {
  std::string out;
  for (char c : type_name) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out;
}

/** Registers a bench type; a refusal is said (its rows then fail naming the type). */
inline void addBenchType(const std::string& id, apex::Manifest m, std::function<std::unique_ptr<apex::Node>()> make) {
  if (auto st = benchRegistry().add(id, std::move(m), std::move(make)); !st) std::fprintf(stderr, "%s\n", st.message().c_str());
}

/** The id of a Feed with outputs of types Ts..., registered on first use. */
template <class... Ts>
std::string feedType() {
  static const std::string id = [] {
    std::string name = "bench/Feed";
    apex::Manifest m;
    int i = 0;
    ((m.output<Ts>("o" + std::to_string(i++)), name += "_" + idPart(apex::typeOf<Ts>()->name)), ...);
    m.driven();
    addBenchType(name, std::move(m), [] { return std::make_unique<Feed>(); });
    return name;
  }();
  return id;
}

/** Counts what arrives (Nothing too: a node that fails sends it) and drops it at once, so the
 *  node's output buffer is free again for the next frame. */
class SinkBase : public apex::Node {
 public:
  void process() override {
    std::lock_guard<std::mutex> l(m_);
    ++count_;
    cv_.notify_all();
  }
  /** False if the n-th message has not come within 60 s. */
  bool waitFor(long n) {
    std::unique_lock<std::mutex> l(m_);
    return cv_.wait_for(l, std::chrono::seconds(60), [&] { return count_ >= n; });
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  long count_ = 0;
};

/** The id of a sink with one optional input "in" of type T, registered on first use. */
template <class T>
std::string sinkType() {
  static const std::string id = [] {
    const std::string name = "bench/Sink_" + idPart(apex::typeOf<T>()->name);
    addBenchType(name, apex::Manifest().optionalInput<T>("in"), [] { return std::make_unique<SinkBase>(); });
    return name;
  }();
  return id;
}

/** One node type on one kind of input, and the library call it stands for. */
struct NodeCase {
  std::string label;  ///< the row's name: the type's, or with the variant ("Rotate 15°")
  std::string type;  ///< e.g. "apex_nodes/GaussianBlur"
  std::string input;  ///< what it is fed, in words
  std::string feed;  ///< feedType<...>() of the inputs' types
  std::vector<std::string> in_ports;  ///< the node's input for each of the feed's outputs
  std::vector<std::vector<apex::Message>> frames;  ///< per firing, one message per feed output; cycled
  Params params;
  std::string out_port;  ///< the output the sink takes
  std::string sink;  ///< sinkType<...>() of that output
  std::string call_text;  ///< the call in words
  std::function<void(std::size_t)> call;  ///< the call on frame i's data, keeping its outputs between frames
  std::string why_not;  ///< set: no figures, this reason instead
  std::string over;  ///< why it may miss the goal: work the call does not do (said in the row if it does)
};

/** The case with the reason it may miss the goal. */
inline NodeCase over(NodeCase c, std::string why) {
  c.over = std::move(why);
  return c;
}

/** A node of several inputs fed the same messages each frame: `in_ports` name the node's input
 *  for each message; `feed` is feedType<...>() of their types. */
inline NodeCase fixedCase(std::string label, std::string type, std::string input, std::string feed,
                          std::vector<std::string> in_ports, std::vector<apex::Message> messages, Params params,
                          std::string out_port, std::string sink, std::string call_text, std::function<void()> call) {
  NodeCase c;
  c.label = std::move(label);
  c.type = std::move(type);
  c.input = std::move(input);
  c.feed = std::move(feed);
  c.in_ports = std::move(in_ports);
  c.frames = {std::move(messages)};
  c.params = std::move(params);
  c.out_port = std::move(out_port);
  c.sink = std::move(sink);
  c.call_text = std::move(call_text);
  c.call = [call = std::move(call)](std::size_t) { call(); };
  return c;
}

/** A case that is not measured: a row with the reason. */
inline NodeCase notMeasured(std::string label, std::string input, std::string call_text, std::string why) {
  NodeCase c;
  c.label = std::move(label);
  c.input = std::move(input);
  c.call_text = std::move(call_text);
  c.why_not = std::move(why);
  return c;
}

/** Feed → the node → sink in one thread group, one frame in flight. */
class NodeRun {
 public:
  explicit NodeRun(const NodeCase& c) {
    auto check = [this](const apex::Status& s) {
      if (!s && error.empty()) error = s.message();
    };
    check(g_.addNode(c.feed, "src").status());
    check(g_.addNode(c.type, "node").status());
    check(g_.addNode(c.sink, "sink").status());
    for (const auto& [p, v] : c.params) check(g_.setParameter("node", p, v).status());
    for (std::size_t i = 0; i < c.in_ports.size(); ++i) check(g_.connect("src", "o" + std::to_string(i), "node", c.in_ports[i]));
    check(g_.connect("node", c.out_port, "sink", "in"));
    if (!error.empty()) return;
    src_ = static_cast<Feed*>(g_.nodeObject("src"));
    sink_ = static_cast<SinkBase*>(g_.nodeObject("sink"));
    g_.start();
  }
  ~NodeRun() {
    if (src_) g_.stop();
  }

  /** Feeds one frame's messages and waits for the node's output at the sink; returns the
   *  node's firing as the runtime timed it (NodeStats::last_ns), µs; or -1 and `error`. */
  double fire(const std::vector<apex::Message>& frame) {
    src_->next = frame;
    src_->notifyNewData();
    if (!sink_->waitFor(++sent_)) {
      error = "no output within 60 s";
      return -1;
    }
    for (const apex::NodeStats& s : g_.nodeStats(3600)) {
      if (s.name != "node") continue;
      if (!s.error.empty()) error = s.error;
      else if (s.firings != ++firings_) error = "the node did not fire on the frame";
      return error.empty() ? double(s.last_ns) / 1e3 : -1;
    }
    error = "no statistics for the node";
    return -1;
  }

  std::string error;

 private:
  apex::Graph g_{benchRegistry()};
  Feed* src_ = nullptr;
  SinkBase* sink_ = nullptr;
  long sent_ = 0;
  std::uint64_t firings_ = 0;
};

/** How long and how often: rounds of N frames per side, N from the call's time. */
struct Budget {
  int rounds, min_frames, max_frames;
  double per_block_us;
  static Budget of(bool quick) { return quick ? Budget{3, 3, 30, 20e3} : Budget{7, 5, 100, 80e3}; }
};

inline const char* kTableHead =
    "| node | input | call | frames × rounds | call µs | node µs | node / call | within goal |\n"
    "|---|---|---|---|---|---|---|---|\n";

/** Measures one case, interleaved (node, call, node, call, ...), and prints its table row.
 *  Adds its label to `outside` if it misses the goal (node ≤ call × 1.05 + 20 µs, medians),
 *  to `failed` if the node failed, to `skipped` if it has a reason instead of figures. */
inline void measureRow(const NodeCase& c, const Budget& b, std::vector<std::string>& outside, std::vector<std::string>& failed,
                       std::vector<std::string>& skipped) {
  using Clock = std::chrono::steady_clock;
  if (!c.why_not.empty()) {
    std::printf("| %s | %s | %s | | | | | not measured: %s |\n", c.label.c_str(), c.input.c_str(), c.call_text.c_str(),
                c.why_not.c_str());
    skipped.push_back(c.label);
    return;
  }
  NodeRun node(c);
  std::size_t next_node = 0, next_call = 0;
  auto fireNode = [&] { return node.fire(c.frames[next_node++ % c.frames.size()]); };
  auto fireCall = [&] {
    const auto t0 = Clock::now();
    c.call(next_call++ % c.frames.size());
    return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
  };
  double call_us = 0;
  for (int i = 0; i < 5 && node.error.empty(); ++i) {  // warm up: first allocations, models, caches
    fireNode();
    call_us = fireCall();
  }
  Spread call, nodes, ratio;
  const int n = std::clamp(static_cast<int>(b.per_block_us / std::max(call_us, 1.0)), b.min_frames, b.max_frames);
  for (int r = 0; r < b.rounds && node.error.empty(); ++r) {
    Spread fn, fc;
    for (int i = 0; i < n && node.error.empty(); ++i) fn.add(fireNode());
    for (int i = 0; i < n; ++i) fc.add(fireCall());
    if (!node.error.empty()) break;
    nodes.add(fn.median());
    call.add(fc.median());
    ratio.add(fn.median() / fc.median());
  }
  if (!node.error.empty()) {
    std::printf("| %s | %s | %s | | | | | failed: %s |\n", c.label.c_str(), c.input.c_str(), c.call_text.c_str(),
                node.error.c_str());
    failed.push_back(c.label);
    return;
  }
  const bool within = nodes.median() <= call.median() * 1.05 + 20;
  if (!within) outside.push_back(c.label);
  const char* fmt = call.median() < 100 ? "%.1f" : "%.0f";
  std::printf("| %s | %s | %s | %d × %d | %s | %s | %.2fx (%.2f–%.2f) | %s |\n", c.label.c_str(), c.input.c_str(),
              c.call_text.c_str(), n, b.rounds, call.text(fmt).c_str(), nodes.text(fmt).c_str(), ratio.median(), ratio.min(),
              ratio.max(),
              within           ? "yes"
              : c.over.empty() ? "no"
                               : ("no: " + c.over).c_str());
  std::fflush(stdout);
}

/** The table's rows, then a line naming the rows outside the goal, failed or not measured. */
/** While it lives, the calling thread (and the threads it starts: a graph's group threads) runs on
 *  one core: the node on its group's thread and the call on this one then see the same caches.
 *  (On two cores a ~0.1 ms memory-bound call ran 20-40 us slower as a node, its frame in the
 *  other core's cache, e.g. Flip 1.30x on two cores against 1.08x on one.) */
class OneCore {
 public:
  OneCore() {
    ok_ = sched_getaffinity(0, sizeof before_, &before_) == 0;
    if (!ok_) return;
    cpu_set_t one;
    CPU_ZERO(&one);
    for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
      if (CPU_ISSET(cpu, &before_)) {
        CPU_SET(cpu, &one);
        break;
      }
    ok_ = sched_setaffinity(0, sizeof one, &one) == 0;
  }
  ~OneCore() {
    if (ok_) sched_setaffinity(0, sizeof before_, &before_);
  }
  OneCore(const OneCore&) = delete;
  OneCore& operator=(const OneCore&) = delete;

 private:
  cpu_set_t before_;
  bool ok_ = false;
};

inline void measureTable(const std::vector<NodeCase>& cases, const Budget& b) {
  const OneCore one_core;
  std::printf("%s", kTableHead);
  std::vector<std::string> outside, failed, skipped;
  // APEX_BENCH_ONLY=Name[,Name...]: only these rows (to profile one node alone)
  const char* only = std::getenv("APEX_BENCH_ONLY");
  const std::string wanted = only ? "," + std::string(only) + "," : "";
  for (const NodeCase& c : cases)
    if (wanted.empty() || wanted.find("," + c.label + ",") != std::string::npos) measureRow(c, b, outside, failed, skipped);
  auto list = [](const std::vector<std::string>& names) {
    std::string s;
    for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
    return names.empty() ? std::string("none") : s;
  };
  if (outside.empty() && failed.empty()) std::printf("\nEvery node measured is within the goal in this run.");
  else std::printf("\nOutside the goal in this run: %s; failed: %s.", list(outside).c_str(), list(failed).c_str());
  std::printf(
      " Not measured (the row says why): %s. Node and call ran on one core (the bench's thread and the\n"
      "graph's pinned together), so both found the frame in the same caches.\n",
      list(skipped).c_str());
}

}  // namespace apex_bench
