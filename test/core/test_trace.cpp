// The frame trace: messages name their frame (Message::frame), each thread group keeps its last
// firings while tracing is on, and the trace reads as Chrome trace event JSON with flows per frame.
#include <gmock/gmock.h>

#include <atomic>
#include <chrono>
#include <climits>
#include <thread>

#include "../../apex_runtime/src/core/trace_ring.hpp"
#include "apex/core/histogram.hpp"
#include "apex_test/test_nodes.hpp"

using namespace apex_test;
using ::testing::HasSubstr;

namespace {

/** A payload with its own stamp, as an image with a ROS header. */
struct Frame {
  std::int64_t stamp;
  int value;
};

/** A driven source of stamped frames: send(stamp, value); `later` sends each 5 ms later stamped,
 *  as a bag's cloud beside its image. */
class FrameSource : public Node {
 public:
  static Manifest manifest() { return Manifest("sends stamped frames").output<Frame>("out").output<Frame>("later").driven(); }
  void send(std::int64_t stamp, int value) {
    {
      std::lock_guard<std::mutex> l(m_);
      queue_.push_back({stamp, value});
    }
    notifyNewData();
  }
  void process() override {
    std::lock_guard<std::mutex> l(m_);
    if (queue_.empty()) return;
    publish("out", queue_.front());
    publish("later", Frame{queue_.front().stamp + 5000000, queue_.front().value});
    queue_.pop_front();
    if (!queue_.empty()) notifyNewData();
  }

 private:
  std::mutex m_;
  std::deque<Frame> queue_;
};

/** A frame's value: an int, which has no stamp of its own. */
class Unwrap : public Node {
 public:
  static Manifest manifest() { return Manifest("a frame's value").input<Frame>("in").output<int>("out"); }
  void process() override { publish("out", input<Frame>("in")->value); }
};

/** A frame's value on `all`, and on `even` only when it is even (an output sending on some frames). */
class Evens : public Node {
 public:
  static Manifest manifest() {
    return Manifest("a frame's value; the even ones apart").input<Frame>("in").output<int>("all").output<int>("even");
  }
  void process() override {
    const int v = input<Frame>("in")->value;
    publish("all", v);
    if (v % 2 == 0) publish("even", v);
  }
};

NodeRegistry registry() {
  readStampWith<Frame>([](const void* p) { return static_cast<const Frame*>(p)->stamp; });
  NodeRegistry r = testRegistry();
  EXPECT_TRUE(r.add<FrameSource>("test/FrameSource"));
  EXPECT_TRUE(r.add<Unwrap>("test/Unwrap"));
  EXPECT_TRUE(r.add<Evens>("test/Evens"));
  return r;
}

/** source -> unwrap (group "camera") -> gain -> sink (group "detect"). */
void build(Graph& g) {
  add(g, "test/FrameSource", "source", "camera");
  add(g, "test/Unwrap", "unwrap", "camera");
  add(g, "test/Gain", "gain", "detect");
  add(g, "test/Collector", "sink", "detect");
  link(g, "source", "out", "unwrap", "in");
  link(g, "unwrap", "out", "gain", "in");
  link(g, "gain", "out", "sink", "in");
}

void play(Graph& g, int frames) {
  auto* sink = object<Collector>(g, "sink");
  const std::size_t before = sink->size();
  for (int i = 1; i <= frames; ++i) object<FrameSource>(g, "source")->send(1000000000LL * i, i);
  ASSERT_TRUE(sink->waitFor(before + frames));
  ASSERT_TRUE(g.waitIdle(kWait));
}

TEST(Trace, AMessageNamesTheFrameItCameFromThroughNodesWhoseOutputHasNoStamp) {
  Graph g(registry());
  build(g);
  add(g, "test/Collector", "later_sink", "detect");
  link(g, "source", "later", "later_sink", "in");
  g.start();
  play(g, 3);
  std::vector<std::int64_t> frames, later;
  for (const auto& m : object<Collector>(g, "sink")->messages()) frames.push_back(m.frame());
  EXPECT_EQ(frames, (std::vector<std::int64_t>{1000000000, 2000000000, 3000000000}));
  // what one firing of a source sends is one frame: named by its first stamped message
  ASSERT_TRUE(object<Collector>(g, "later_sink")->waitFor(3));
  for (const auto& m : object<Collector>(g, "later_sink")->messages()) later.push_back(m.frame());
  EXPECT_EQ(later, frames);
  EXPECT_EQ(Message::make(5).frame(), 0);  // made by a node, not yet sent: no frame
}

TEST(Trace, OffByDefaultOnItKeepsEveryGroupsFiringsWithTheirFrames) {
  Graph g(registry());
  build(g);
  g.start();
  play(g, 2);
  EXPECT_FALSE(g.tracing());
  EXPECT_EQ(g.trace().size(), 0u);
  g.setTracing(true);
  EXPECT_TRUE(g.tracing());
  play(g, 3);
  g.setTracing(false);
  play(g, 2);  // not kept
  const Trace t = g.trace();
  ASSERT_EQ(t.groups.size(), 2u);  // the default group, which fired nothing, is left out
  std::map<std::string, std::vector<std::int64_t>> frames;  // node -> the frames of its firings
  for (const auto& group : t.groups) {
    for (const auto& f : group.firings) {
      frames[f.node].push_back(f.frame);
      EXPECT_LE(f.start_ns, f.end_ns);
      EXPECT_EQ(group.name, f.node == "source" || f.node == "unwrap" ? "camera" : "detect") << f.node;
    }
  }
  const std::vector<std::int64_t> three{1000000000, 2000000000, 3000000000};
  for (const char* node : {"source", "unwrap", "gain", "sink"}) EXPECT_EQ(frames[node], three) << node;
  for (const auto& group : t.groups)
    for (const auto& f : group.firings) EXPECT_EQ(f.starts_frame, f.node == "source") << f.node;
  EXPECT_EQ(t.groups[0].firings.front().type, t.groups[0].name == "camera" ? "test/FrameSource" : "test/Gain");
}

TEST(Trace, ChromeJsonHasATrackPerGroupAndAFlowPerFrameAcrossThem) {
  Graph g(registry());
  build(g);
  g.setTracing(true);
  g.start();
  play(g, 3);
  play(g, 1);  // frame 1 again (a bag in a loop): a flow of its own
  const std::string json = chromeTraceJson(g.trace(), "apex \"test\"");
  EXPECT_THAT(json, HasSubstr("\"name\":\"process_name\",\"pid\":1,\"tid\":0,\"args\":{\"name\":\"apex \\\"test\\\"\"}"));
  EXPECT_THAT(json, HasSubstr("\"args\":{\"name\":\"thread group camera\"}"));
  EXPECT_THAT(json, HasSubstr("\"args\":{\"name\":\"thread group detect\"}"));
  EXPECT_THAT(json, HasSubstr("{\"ph\":\"X\",\"name\":\"gain\",\"cat\":\"test/Gain\",\"pid\":1,\"tid\":"));
  EXPECT_THAT(json, HasSubstr("\"args\":{\"frame\":\"3.000000000\"}"));
  auto count = [&](const std::string& s) {
    std::size_t n = 0;
    for (auto at = json.find(s); at != std::string::npos; at = json.find(s, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("\"ph\":\"X\""), 16u);
  EXPECT_EQ(count("\"ph\":\"s\""), 4u);  // one flow per frame passing: 1, 2, 3 and 1 again
  EXPECT_EQ(count("\"ph\":\"t\""), 8u);  // source -> unwrap -> gain -> sink
  EXPECT_EQ(count("\"ph\":\"f\",\"name\":\"frame\",\"cat\":\"frame\",\"id\":"), 4u);
}

TEST(Trace, ARemovedNodeIsNamedAsSuchAndSecondsKeepOnlyTheNewest) {
  Graph g(registry());
  build(g);
  g.setTracing(true);
  g.start();
  play(g, 1);
  std::this_thread::sleep_for(1s);  // the first firings end 1 s before the trace is read
  add(g, "test/Feeder", "late", "idle");  // a group made while tracing traces too
  object<Feeder>(g, "late")->feed(1);
  ASSERT_TRUE(waitUntil([&] { return g.trace(0.5).size() > 0; }));
  for (const auto& group : g.trace(0.5).groups) EXPECT_TRUE(group.name == "idle" || group.firings.empty()) << group.name;
  ASSERT_TRUE(g.removeNode("late"));
  bool removed = false;
  for (const auto& group : g.trace().groups)
    for (const auto& f : group.firings) removed = removed || (f.node == "(removed)" && group.name == "idle");
  EXPECT_TRUE(removed);
}

std::int64_t wallNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

NodeStats statsOf(const Graph& g, const std::string& node) {
  for (const auto& s : g.nodeStats(1e9))
    if (s.name == node) return s;
  ADD_FAILURE() << "no node " << node;
  return {};
}

/** The graph built, started, and 20 frames sent through it, each stamped 30 ms ago. */
void sendTwentyFramesStamped30msAgo(Graph& g) {
  build(g);
  g.start();
  for (int i = 0; i < 20; ++i) object<FrameSource>(g, "source")->send(wallNs() - 30000000, i);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(20));
  ASSERT_TRUE(g.waitIdle(kWait));
}

TEST(Latency, FromTheFramesStampToTheEndOfEachFiringThatWorkedOnIt) {
  Graph g(registry());
  ASSERT_NO_FATAL_FAILURE(sendTwentyFramesStamped30msAgo(g));
  auto* source = object<FrameSource>(g, "source");
  const std::int64_t waited = 1000000000;  // what a loaded machine may add, at most (a passing run: < 1 ms)
  for (const char* node : {"source", "unwrap", "gain", "sink"}) {
    const NodeStats s = statsOf(g, node);
    EXPECT_EQ(s.latency_frames, 20u) << node;
    EXPECT_GE(s.latency_mean_ns, 30000000) << node;
    EXPECT_LT(s.latency_mean_ns, 30000000 + waited) << node;
    EXPECT_GE(s.latency_p50_ns, 30000000 * 15 / 16) << node;
    EXPECT_LE(s.latency_p50_ns, s.latency_p95_ns) << node;
    EXPECT_LE(s.latency_p95_ns, s.latency_max_ns) << node;
  }
  // the sink is done with a frame after the source: its latency is the larger
  EXPECT_GE(statsOf(g, "sink").latency_mean_ns, statsOf(g, "source").latency_mean_ns);
  EXPECT_GT(statsOf(g, "gain").p50_ns, 0u);
  EXPECT_LE(statsOf(g, "gain").p50_ns, statsOf(g, "gain").p95_ns);
  source->countDropped(3);  // a source that keeps the newest lost three (any thread may say so)
  EXPECT_EQ(statsOf(g, "source").dropped, 3u);
  EXPECT_EQ(statsOf(g, "sink").dropped, 0u);
}

TEST(Latency, EachOutputHasItsOwnOverTheFiringsThatSentOnIt) {
  Graph g(registry());
  add(g, "test/FrameSource", "source");
  add(g, "test/Evens", "evens");
  add(g, "test/Collector", "sink");
  link(g, "source", "out", "evens", "in");
  link(g, "evens", "all", "sink", "in");
  g.start();
  for (int i = 0; i < 20; ++i) object<FrameSource>(g, "source")->send(wallNs() - 30000000, i);
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(20));
  ASSERT_TRUE(g.waitIdle(kWait));
  const NodeStats s = statsOf(g, "evens");
  ASSERT_EQ(s.outputs.size(), 2u);
  const OutputStats &all = s.outputs[0], &even = s.outputs[1];
  EXPECT_EQ(all.name, "all");
  EXPECT_EQ(even.name, "even");
  EXPECT_EQ(s.latency_frames, 20u);
  EXPECT_EQ(all.latency_frames, 20u);
  EXPECT_EQ(even.sent, 10u);
  EXPECT_EQ(even.latency_frames, 10u) << "only the firings that sent on it";
  for (const OutputStats* o : {&all, &even}) {
    EXPECT_GE(o->latency_p50_ns, 30000000 * 15 / 16) << o->name;
    EXPECT_LE(o->latency_p50_ns, o->latency_p95_ns) << o->name;
    EXPECT_LE(o->latency_p95_ns, o->latency_max_ns) << o->name;
  }
  EXPECT_EQ(all.latency_p95_ns, s.latency_p95_ns) << "every firing sent on it: the node's own";
  const NodeStats sink = statsOf(g, "sink");
  EXPECT_TRUE(sink.outputs.empty());
  const NodeStats source = statsOf(g, "source");
  ASSERT_EQ(source.outputs.size(), 2u);
  EXPECT_EQ(source.outputs[1].latency_frames, 20u) << "unconnected, it still sent";
}

TEST(Latency, ANodesProfileIsItsHistogramsOverTheStatusWindow) {
  Graph g(registry());
  ASSERT_NO_FATAL_FAILURE(sendTwentyFramesStamped30msAgo(g));
  auto profile = g.nodeProfile("sink");
  ASSERT_TRUE(profile) << profile.message();
  const NodeProfile& p = profile.value();
  EXPECT_EQ(p.name, "sink");
  EXPECT_GT(p.window_s, 0);
  std::uint64_t frames = 0, timed = 0;
  for (const auto& b : p.latency) {
    frames += b.count;
    EXPECT_LT(b.lower_ns, b.upper_ns);
    EXPECT_GE(b.upper_ns, 30000000) << "no frame is younger than its 30 ms";
  }
  EXPECT_EQ(frames, statsOf(g, "sink").latency_frames);
  EXPECT_EQ(frames, 20u);
  for (const auto& b : p.time) timed += b.count;
  EXPECT_GT(timed, 0u);
  for (std::size_t i = 1; i < p.latency.size(); ++i) EXPECT_LE(p.latency[i - 1].upper_ns, p.latency[i].lower_ns) << "in order";
  EXPECT_THAT(g.nodeProfile("ghost").message(), HasSubstr("no node named 'ghost'"));
}

TEST(Histogram, ABucketsBoundsHoldWhatItCounts) {
  for (std::int64_t ns : {0LL, 1023LL, 1024LL, 5000LL, 8191LL, 8192LL, 123456789LL}) {
    const int b = HistogramCounts::bucket(ns);
    EXPECT_LE(HistogramCounts::lowerNs(b), double(ns)) << ns;
    EXPECT_GT(HistogramCounts::upperNs(b), double(ns)) << ns;
    EXPECT_EQ(HistogramCounts::upperNs(b), HistogramCounts::lowerNs(b + 1)) << ns;
  }
}

TEST(Latency, NoneForFramesStampedLongAgoAsABagPlayedAtItsRecordedTimes) {
  Graph g(registry());
  build(g);
  g.start();
  object<FrameSource>(g, "source")->send(1700000000000000000LL, 1);  // 2023
  ASSERT_TRUE(object<Collector>(g, "sink")->waitFor(1));
  ASSERT_TRUE(g.waitIdle(kWait));
  const NodeStats s = statsOf(g, "sink");
  EXPECT_EQ(s.latency_frames, 0u);
  EXPECT_EQ(s.latency_mean_ns, -1);
  EXPECT_EQ(s.latency_p95_ns, -1);
  EXPECT_EQ(statsOf(g, "gain").firings, 1u);
}

TEST(Histogram, QuantilesWithinASixteenthOfTheValue) {
  Histogram h;
  for (int i = 1; i <= 1000; ++i) h.add(std::int64_t(i) * 100000);  // 0.1 .. 100 ms
  const HistogramCounts c = h.read();
  EXPECT_EQ(c.total(), 1000u);
  EXPECT_NEAR(c.quantileNs(0.5), 50e6, 50e6 / 16);
  EXPECT_NEAR(c.quantileNs(0.95), 95e6, 95e6 / 16);
  EXPECT_NEAR(c.quantileNs(1.0), 100e6, 100e6 / 16);
  EXPECT_EQ(HistogramCounts::bucket(0), 0);
  EXPECT_EQ(HistogramCounts::bucket(INT64_MAX), HistogramCounts::kBuckets - 1);  // the last holds the rest
  for (int b = 1; b < HistogramCounts::kBuckets; ++b) EXPECT_GT(HistogramCounts::middleNs(b), HistogramCounts::middleNs(b - 1));
  Histogram later;  // a window: what came since an earlier reading
  later.add(5000000);
  const HistogramCounts first = later.read();
  later.add(80000000);
  EXPECT_NEAR(later.read().since(first).quantileNs(0.5), 80e6, 80e6 / 16);
  EXPECT_EQ(HistogramCounts().quantileNs(0.5), 0);
}

TEST(TraceRing, KeepsTheNewestFiringsAndNeverOneHalfWritten) {
  detail::TraceRing small(4);
  for (int i = 0; i < 10; ++i) small.write({std::uint64_t(i), i, i + 1, i * 10});
  auto kept = small.read();
  ASSERT_EQ(kept.size(), 3u);  // the newest but one slot may be in writing: only 3 of 4 are sure
  EXPECT_EQ(kept.front().node, 7u);
  EXPECT_EQ(kept.back().frame, 90);
  // A writer racing readers: every record read is whole (its fields agree).
  detail::TraceRing ring(64);
  std::atomic<bool> stop{false};
  std::thread writer([&] {
    for (std::int64_t i = 0; !stop.load(); ++i) ring.write({std::uint64_t(i), i, i + 1, i * 10});
  });
  std::size_t read = 0;
  for (int k = 0; k < 2000 || read < 100000; ++k)
    for (const auto& r : ring.read()) {
      ASSERT_EQ(r.start, std::int64_t(r.node));
      ASSERT_EQ(r.end, r.start + 1);
      ASSERT_EQ(r.frame, r.start * 10);
      ++read;
    }
  stop = true;
  writer.join();
  EXPECT_GT(read, 0u);
}

}  // namespace
