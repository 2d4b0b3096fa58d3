// Core benchmarks; every figure is a ratio against a baseline measured in the
// same run. Prints a markdown report (docs/benchmarks.md is made from it by
// scripts/bench).
//   apex_bench_core [--quick] [--hop] [--size]   (--hop, --size: only that table)
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "apex/core/graph.hpp"
#include "apex/core/graph_file.hpp"
#include "spread.hpp"

#ifdef APEX_BENCH_TBB
#include <tbb/flow_graph.h>
#include <tbb/global_control.h>
#endif

using namespace apex;
using Clock = std::chrono::steady_clock;
using apex_bench::Spread;

namespace {

double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// ---------------------------------------------------------------- nodes

struct Source : Node {  // free-running: a new message whenever its receivers have read the last
  static Manifest manifest() { return Manifest().output<int>("out"); }
  void process() override { publish("out", n_++); }
  int n_ = 0;
};

struct Feed : Node {  // driven: one message per notifyNewData()
  static Manifest manifest() { return Manifest().output<int>("out").driven(); }
  void process() override { publish("out", n_++); }
  int n_ = 0;
};

struct Relay : Node {
  static Manifest manifest() { return Manifest().input<int>("in").output<int>("out"); }
  void process() override { publishMessage("out", inputMessage("in")); }
};

struct HandleRelay : Node {  // the same, through typed handles (ports.hpp)
  static Manifest manifest() { return Manifest().input<int>("in").output<int>("out"); }
  void process() override { out_.publishMessage(in_.message()); }
  Input<int> in_{this, "in"};
  Output<int> out_{this, "out"};
};

struct TakeRelay : Node {  // the same, moving the message on (Input::take)
  static Manifest manifest() { return Manifest().input<int>("in").output<int>("out"); }
  void process() override { out_.publishMessage(in_.take()); }
  Input<int> in_{this, "in"};
  Output<int> out_{this, "out"};
};

struct Work : Node {  // ~2 ms of busy work, a stand-in for an image filter
  static Manifest manifest() { return Manifest().input<int>("in").output<int>("out"); }
  void process() override {
    const auto end = Clock::now() + std::chrono::microseconds(2000);
    while (Clock::now() < end) {
    }
    publishMessage("out", inputMessage("in"));
  }
};

struct Sink : Node {  // counts, and wakes the benchmark at the target
  static Manifest manifest() { return Manifest().input<int>("in"); }
  void process() override {
    std::lock_guard<std::mutex> l(m);
    if (++count == target) {
      done = Clock::now();  // the waiter's wake-up (~21 µs, ms when its core is busy) is not the chain's
      cv.notify_all();
    }
  }
  void waitFor(long n) {
    std::unique_lock<std::mutex> l(m);
    target = n;
    if (count >= n) done = Clock::now();  // passed already (not in a benchmark's long run)
    cv.wait(l, [&] { return count >= n; });
  }
  std::mutex m;
  std::condition_variable cv;
  long count = 0, target = -1;
  Clock::time_point done;  // when the target was reached
};

NodeRegistry registry() {
  NodeRegistry r;
  (void)r.add<Source>("bench/Source");
  (void)r.add<Feed>("bench/Feed");
  (void)r.add<Relay>("bench/Relay");
  (void)r.add<HandleRelay>("bench/HandleRelay");
  (void)r.add<TakeRelay>("bench/TakeRelay");
  (void)r.add<Work>("bench/Work");
  (void)r.add<Sink>("bench/Sink");
  return r;
}

/** source → k relays → sink; relays from index `split` on go to group "b". */
void chain(Graph& g, const char* source, int k, int split = 1 << 30, const char* relay = "bench/Relay") {
  (void)g.addNode(source, "src");
  std::string prev = "src";
  for (int i = 0; i < k; ++i) {
    const std::string name = "r" + std::to_string(i);
    (void)g.addNode(relay, name, i >= split ? "b" : "");
    (void)g.connect(prev, "out", name, "in");
    prev = name;
  }
  (void)g.addNode("bench/Sink", "sink", k >= split ? "b" : "");
  (void)g.connect(prev, "out", "sink", "in");
}

// ---------------------------------------------------------------- 1. overhead per hop

double baselineHopNs(int k, long messages) {
  std::vector<std::function<std::shared_ptr<const int>(std::shared_ptr<const int>)>> fns(
      k, [](std::shared_ptr<const int> m) { return m; });
  long sum = 0;
  const auto t0 = Clock::now();
  for (long i = 0; i < messages; ++i) {
    auto m = std::make_shared<const int>(static_cast<int>(i));
    for (auto& f : fns) m = f(std::move(m));
    sum += *m;
  }
  const auto t1 = Clock::now();
  if (sum == 42) std::puts("");  // keep the loop
  return seconds(t0, t1) * 1e9 / double(messages) / k;
}

#ifdef APEX_BENCH_TBB
/** The same chain in TBB's flow_graph: an input_node and k serial function_nodes, one thread. */
double tbbHopNs(int k, long messages) {
  using Msg = std::shared_ptr<const int>;
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  tbb::flow::graph g;
  long produced = 0, sum = 0;
  tbb::flow::input_node<Msg> src(g, [&](tbb::flow_control& fc) -> Msg {
    if (produced == messages) {
      fc.stop();
      return nullptr;
    }
    return std::make_shared<const int>(static_cast<int>(produced++));
  });
  std::vector<std::unique_ptr<tbb::flow::function_node<Msg, Msg>>> relays;
  for (int i = 0; i < k; ++i) {
    relays.push_back(std::make_unique<tbb::flow::function_node<Msg, Msg>>(g, tbb::flow::serial, [](Msg m) { return m; }));
    if (i == 0) tbb::flow::make_edge(src, *relays[0]);
    else tbb::flow::make_edge(*relays[i - 1], *relays[i]);
  }
  tbb::flow::function_node<Msg> sink(g, tbb::flow::serial, [&](Msg m) { sum += *m; });
  tbb::flow::make_edge(*relays.back(), sink);
  const auto t0 = Clock::now();
  src.activate();
  g.wait_for_all();
  const auto t1 = Clock::now();
  if (sum == 42) std::puts("");
  return seconds(t0, t1) * 1e9 / double(messages) / k;
}
#endif

/** Runs a built chain of k hops until its sink has `messages`: ns per message per hop. */
double runChain(Graph& g, int k, long messages) {
  auto* sink = static_cast<Sink*>(g.nodeObject("sink"));
  const auto t0 = Clock::now();
  g.start();
  sink->waitFor(messages);
  const auto t1 = sink->done;  // TBB's chain ends on the measuring thread: no wake-up there either
  g.stop();
  return seconds(t0, t1) * 1e9 / double(messages) / k;
}

double apexHopNs(int k, long messages, const char* relay = "bench/Relay", bool traced = false) {
  Graph g(registry());
  chain(g, "bench/Source", k, 1 << 30, relay);
  g.setTracing(traced);
  return runChain(g, k, messages);
}

/** The same chain with every relay alone in a subgraph (its ports exported): each hop crosses
 *  two subgraph boundaries, out of one and into the next. */
double subgraphHopNs(int k, long messages) {
  GraphDescription d;
  d.nodes.push_back({});
  d.nodes.back().name = "src", d.nodes.back().type = "bench/Source";
  auto part = std::make_shared<GraphDescription>();
  part->nodes.push_back({});
  part->nodes.back().name = "r", part->nodes.back().type = "bench/Relay";
  part->exports = {{ExportDescription::Kind::Input, "in", {"r/in"}, "", 0},
                   {ExportDescription::Kind::Output, "out", {"r/out"}, "", 0}};
  std::string prev = "src";
  for (int i = 0; i < k; ++i) {
    NodeDescription n;
    n.name = "s" + std::to_string(i), n.type = kSubgraphType, n.subgraph = part;
    d.nodes.push_back(n);
    d.connections.push_back({prev, "out", n.name, "in", 0});
    prev = n.name;
  }
  d.nodes.push_back({});
  d.nodes.back().name = "sink", d.nodes.back().type = "bench/Sink";
  d.connections.push_back({prev, "out", "sink", "in", 0});
  Graph g(registry());
  if (auto st = g.load(d); !st) {
    std::fprintf(stderr, "subgraph chain: %s\n", st.message().c_str());
    std::exit(1);
  }
  return runChain(g, k, messages);
}

// ---------------------------------------------------------------- 2. wake-ups per boundary

struct Latency {
  double us_per_message;
  double feed_wakeups;  // of the source's group, woken by the outside feed
  double cross_wakeups;  // of group "b", woken by messages crossing into it
};

Latency oneAtATime(int k, int split, int messages) {
  Graph g(registry());
  chain(g, "bench/Feed", k, split);
  auto* feed = g.nodeObject("src");
  auto* sink = static_cast<Sink*>(g.nodeObject("sink"));
  g.start();
  const auto t0 = Clock::now();
  for (int i = 1; i <= messages; ++i) {
    feed->notifyNewData();
    sink->waitFor(i);
  }
  const auto t1 = Clock::now();
  (void)g.waitIdle(5);
  Latency l{seconds(t0, t1) * 1e6 / messages, 0, 0};
  for (auto& s : g.groupStats()) (s.name == "b" ? l.cross_wakeups : l.feed_wakeups) = double(s.wakeups) / messages;
  g.stop();
  return l;
}

// ---------------------------------------------------------------- 3. pipelining

double pipelineRate(bool two_groups, int messages) {
  Graph g(registry());
  (void)g.addNode("bench/Source", "src");
  (void)g.addNode("bench/Work", "w1");
  (void)g.addNode("bench/Work", "w2", two_groups ? "b" : "");
  (void)g.addNode("bench/Sink", "sink", two_groups ? "b" : "");
  (void)g.connect("src", "out", "w1", "in");
  (void)g.connect("w1", "out", "w2", "in");
  (void)g.connect("w2", "out", "sink", "in");
  auto* sink = static_cast<Sink*>(g.nodeObject("sink"));
  g.start();
  sink->waitFor(5);  // warm up
  const auto t0 = Clock::now();
  sink->waitFor(5 + messages);
  const auto t1 = Clock::now();
  g.stop();
  return messages / seconds(t0, t1);
}

// ---------------------------------------------------------------- 4. graph size

struct SizeRow {
  int n;
  double add_us, connect_us, remove_us, build_ms, save_us, load_us;
};

SizeRow graphSize(int n) {
  Graph g(registry());
  g.start();  // edits on a running graph (its threads idle)
  SizeRow row{n, 0, 0, 0, 0, 0, 0};
  const auto t0 = Clock::now();
  for (int i = 0; i < n; ++i) (void)g.addNode(i == 0 ? "bench/Feed" : "bench/Relay", "n" + std::to_string(i));
  const auto t1 = Clock::now();
  for (int i = 1; i < n; ++i) (void)g.connect("n" + std::to_string(i - 1), "out", "n" + std::to_string(i), "in");
  const auto t2 = Clock::now();
  row.add_us = seconds(t0, t1) * 1e6 / n;
  row.connect_us = seconds(t1, t2) * 1e6 / std::max(1, n - 1);
  row.build_ms = seconds(t0, t2) * 1e3;

  const std::string path = "/tmp/apex_bench_graph_" + std::to_string(n) + ".yaml";
  const auto t3 = Clock::now();
  (void)saveGraphFile(g, path);
  const auto t4 = Clock::now();
  Graph loaded(registry());
  (void)loadGraphFile(loaded, path);
  const auto t5 = Clock::now();
  row.save_us = seconds(t3, t4) * 1e6 / n;
  row.load_us = seconds(t4, t5) * 1e6 / n;
  std::remove(path.c_str());

  const auto t6 = Clock::now();
  for (int i = n - 1; i >= 0; --i) (void)g.removeNode("n" + std::to_string(i));
  const auto t7 = Clock::now();
  row.remove_us = seconds(t6, t7) * 1e6 / n;
  g.stop();
  return row;
}

void printGraphSize() {
  std::printf("\n## Graph size\n\n");
  std::printf(
      "A driven source and a chain of n - 1 relays edited on a started (idle) graph: time per edit, the whole build, and\n");
  std::printf(
      "saving/loading the file. Targets: ≤ 10 µs per edit, 10,000 nodes built in ≤ 100 ms, ≤ 50 µs per node saved or loaded.\n");
  std::printf("Medians of 3 repetitions.\n\n");
  std::printf(
      "| n | add µs | connect µs | remove µs | build ms | save µs/node | load µs/node |\n|---|---|---|---|---|---|---|\n");
  for (int n : {100, 1000, 10000}) {
    Spread add, con, rem, build, save, load;
    for (int r = 0; r < 3; ++r) {
      const SizeRow row = graphSize(n);
      add.add(row.add_us), con.add(row.connect_us), rem.add(row.remove_us);
      build.add(row.build_ms), save.add(row.save_us), load.add(row.load_us);
    }
    std::printf("| %d | %.2f | %.2f | %.2f | %.1f | %.1f | %.1f |\n", n, add.median(), con.median(), rem.median(), build.median(),
                save.median(), load.median());
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, hop_only = false, size_only = false;
  for (int i = 1; i < argc; ++i) {
    quick = quick || std::string(argv[i]) == "--quick";
    hop_only = hop_only || std::string(argv[i]) == "--hop";
    size_only = size_only || std::string(argv[i]) == "--size";
  }
  if (size_only) return printGraphSize(), 0;
  const long hop_messages = quick ? 20000 : 200000;

  const int reps = quick ? 5 : 7;
  std::printf("## Overhead per hop, one thread group\n\n");
  std::printf("A free-running source feeds k relays and a sink, all in one thread group; time per message\n");
  std::printf("end to end divided by k. Baselines in the same run: the same k calls through `std::function`\n");
  std::printf("passing a `shared_ptr` message in a plain loop, and the same chain in TBB's `flow_graph`\n");
  std::printf("(input_node, k serial function_nodes, a sink; one thread, like one group). The variants run\n");
  std::printf("interleaved, %d repetitions each: median (min–max) ns per hop; ratios of the medians.\n", reps);
  std::printf("APEX relays read and write by name (`publishMessage(\"out\", inputMessage(\"in\"))`), or through\n");
  std::printf("typed handles resolved once (`out_.publishMessage(in_.message())`, ports.hpp), or moving the\n");
  std::printf("message on (`out_.publishMessage(in_.take())`: no reference count rise and fall, as the library's\n");
  std::printf("Relay, Switch, Throttle and filters that pass a frame through do).\n\n");
  std::printf(
      "| k | APEX, names | APEX, handles | APEX, take | TBB flow_graph | std::function | names / TBB | handles / TBB | "
      "take / TBB |\n|---|---|---|---|---|---|---|---|---|\n");
  for (int k : {1, 4, 16, 64}) {
    const long m = std::max<long>(2000, hop_messages / k);
    Spread base, tbb, apex_ns, handles_ns, take_ns;
    for (int r = 0; r < reps; ++r) {
      base.add(baselineHopNs(k, m * 10));
#ifdef APEX_BENCH_TBB
      tbb.add(tbbHopNs(k, m));
#endif
      apex_ns.add(apexHopNs(k, m));
      handles_ns.add(apexHopNs(k, m, "bench/HandleRelay"));
      take_ns.add(apexHopNs(k, m, "bench/TakeRelay"));
    }
    const double t = tbb.empty() ? 0.0 : tbb.median();
    auto ratio = [t](const Spread& s) { return t > 0 ? s.median() / t : 0.0; };
    std::printf("| %d | %s | %s | %s | %s | %s | %.2fx | %.2fx | %.2fx |\n", k, apex_ns.text().c_str(), handles_ns.text().c_str(),
                take_ns.text().c_str(), tbb.empty() ? "-" : tbb.text().c_str(), base.text("%.1f").c_str(), ratio(apex_ns),
                ratio(handles_ns), ratio(take_ns));
  }

  std::printf("\n## The frame trace's cost per hop\n\n");
  std::printf("The chain above (APEX, take: the cheapest hop, so the largest share) with the frame trace off and\n");
  std::printf("on (Graph::setTracing: every firing timed and kept in its group's ring), interleaved, %d repetitions:\n", reps);
  std::printf("median (min–max) ns per hop. A firing of a real node takes microseconds to milliseconds; the\n");
  std::printf("demo's frame rate with the trace on and off is in \"What the panel's previews and the frame trace cost\".\n\n");
  std::printf("| k | trace off | trace on | on / off |\n|---|---|---|---|\n");
  for (int k : {1, 16}) {
    const long m = std::max<long>(2000, hop_messages / k);
    Spread off, on;
    for (int r = 0; r < reps; ++r) {
      off.add(apexHopNs(k, m, "bench/TakeRelay"));
      on.add(apexHopNs(k, m, "bench/TakeRelay", true));
    }
    std::printf("| %d | %s | %s | %.2fx |\n", k, off.text().c_str(), on.text().c_str(), on.median() / off.median());
  }
  if (hop_only) return 0;

  std::printf("\n## Overhead per hop through subgraph boundaries\n\n");
  std::printf("The chain above (APEX, names), flat, and with every relay alone in a subgraph that exports its\n");
  std::printf("ports, so each hop leaves one subgraph and enters the next. Subgraphs are flattened (no node\n");
  std::printf("of their own, no hop at the boundary): target 1.0x. Interleaved, %d repetitions: median\n", reps);
  std::printf("(min–max) ns per hop; ratio of the medians.\n\n");
  std::printf("| k | flat | through subgraphs | subgraphs / flat |\n|---|---|---|---|\n");
  for (int k : {4, 16}) {
    const long m = std::max<long>(2000, hop_messages / k);
    Spread flat, grouped;
    for (int r = 0; r < reps; ++r) {
      flat.add(apexHopNs(k, m));
      grouped.add(subgraphHopNs(k, m));
    }
    std::printf("| %d | %s | %s | %.2fx |\n", k, flat.text().c_str(), grouped.text().c_str(), grouped.median() / flat.median());
  }

  std::printf("\n## Thread wake-ups per group boundary\n\n");
  std::printf("One message at a time from outside (notifyNewData, then wait for the sink), 8 relays; the\n");
  std::printf("second row puts relays 4..7 and the sink in group b: one boundary crossed per message.\n");
  std::printf("A wake-up is counted each time a sleeping group thread is notified. With one group the thread\n");
  std::printf("is usually still finishing when the next feed comes, so it rarely sleeps; with two, group\n");
  std::printf("`default` sleeps while b works, so the feed wakes it too.\n\n");
  std::printf("Interleaved, %d repetitions: median (min–max).\n\n", reps);
  std::printf(
      "| layout | latency µs/message | wake-ups of `default` per message | wake-ups of b per message (boundary crossings) "
      "|\n|---|---|---|---|\n");
  const int lat_messages = quick ? 300 : 3000;
  Spread one_us, one_feed, two_us, two_feed, two_cross;
  for (int r = 0; r < reps; ++r) {
    const Latency one = oneAtATime(8, 1 << 30, lat_messages);
    const Latency two = oneAtATime(8, 4, lat_messages);
    one_us.add(one.us_per_message), one_feed.add(one.feed_wakeups);
    two_us.add(two.us_per_message), two_feed.add(two.feed_wakeups), two_cross.add(two.cross_wakeups);
  }
  std::printf("| 1 group | %s | %s | - |\n", one_us.text("%.1f").c_str(), one_feed.text("%.2f").c_str());
  std::printf("| 2 groups | %s | %s | %s |\n", two_us.text("%.1f").c_str(), two_feed.text("%.2f").c_str(),
              two_cross.text("%.2f").c_str());

  std::printf("\n## Pipelining across thread groups\n\n");
  std::printf("Source → work (2 ms busy) → work (2 ms busy) → sink; both works in one group, or the second\n");
  std::printf("work and the sink in a second group. Target: at least 1.8x. Interleaved, %d repetitions:\n", reps);
  std::printf("median (min–max); the ratio is of the medians.\n\n");
  const int pipe_messages = quick ? 100 : 500;
  Spread r1, r2;
  for (int r = 0; r < reps; ++r) {
    r1.add(pipelineRate(false, pipe_messages));
    r2.add(pipelineRate(true, pipe_messages));
  }
  std::printf("| layout | messages/s | ratio |\n|---|---|---|\n| 1 group | %s | 1.00x |\n| 2 groups | %s | %.2fx |\n",
              r1.text("%.1f").c_str(), r2.text("%.1f").c_str(), r2.median() / r1.median());

  printGraphSize();
  return 0;
}
