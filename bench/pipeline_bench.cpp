// The demo pipeline (the paper's Fig. 2 chain) in APEX with 1 and 2 thread
// groups, against the same OpenCV calls hand-written in one loop, measured in
// the same run, with OpenCV's own thread count fixed (1, then its default).
// Then balance (apex/core/balance.hpp): the demo placed by it against one group and
// the hand placement, and generated chains of unequal busy stages placed by it
// against the best of every placement, each run.
//   apex_bench_pipeline [--quick]   (with the devel space sourced: node types come from pluginlib)
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <map>
#include <random>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "apex/core/balance.hpp"
#include "apex/core/graph.hpp"
#include "apex_nodes/types.hpp"
#include "plugin_registry.hpp"
#include "spread.hpp"

using namespace apex;
using apex_nodes::Image;
using Clock = std::chrono::steady_clock;
using apex_bench::Spread;

namespace {

constexpr double kAngle = 15 * M_PI / 180;  // an any-angle rotation (warpAffine), as in PERF_FACTS

std::vector<cv::Mat> frames(int n) {
  std::vector<cv::Mat> out;
  cv::RNG rng(7);
  for (int i = 0; i < n; ++i) {
    cv::Mat m(480, 640, CV_8UC3);
    rng.fill(m, cv::RNG::UNIFORM, 150, 220);
    for (int k = 0; k < 4; ++k)
      cv::rectangle(m, cv::Rect(rng.uniform(20, 520), rng.uniform(20, 360), 80, 80), cv::Scalar::all(30), cv::FILLED);
    out.push_back(m);
  }
  return out;
}

/** The chain written by hand, reusing its buffers: the baseline. */
struct Loop {
  cv::Mat rotated, gray, binary, opened, labels, stats, centroids, overlay;
  cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
  int run(const cv::Mat& frame) {
    const cv::Mat m = cv::getRotationMatrix2D(cv::Point2f(320, 240), kAngle * 180 / M_PI, 1.0);
    cv::warpAffine(frame, rotated, m, frame.size());
    cv::cvtColor(rotated, gray, cv::COLOR_BGR2GRAY);
    cv::adaptiveThreshold(gray, binary, 255, cv::ADAPTIVE_THRESH_MEAN_C, cv::THRESH_BINARY_INV, 11, 2);
    cv::morphologyEx(binary, opened, cv::MORPH_OPEN, kernel);
    const int n = cv::connectedComponentsWithStats(opened, labels, stats, centroids, 8, CV_32S, cv::CCL_DEFAULT);
    rotated.copyTo(overlay);
    int kept = 0;
    for (int i = 1; i < n; ++i)
      if (stats.at<int>(i, cv::CC_STAT_AREA) >= 50) {
        cv::rectangle(overlay, cv::Rect(stats.at<int>(i, 0), stats.at<int>(i, 1), stats.at<int>(i, 2), stats.at<int>(i, 3)),
                      cv::Scalar(0, 255, 0), 2);
        ++kept;
      }
    return kept;
  }
};

/** Feeds frames: one per notifyNewData (latency), or always ready (throughput). */
class FrameSource : public Node {
 public:
  static Manifest manifest() { return Manifest().output<Image>("image").driven(); }
  void process() override {
    auto img = std::make_shared<Image>();
    img->encoding = "bgr8";
    img->mat = (*frames)[i_++ % frames->size()];
    sent = Clock::now();
    publish<Image>("image", img);
    if (free_running) notifyNewData();
  }
  const std::vector<cv::Mat>* frames = nullptr;
  std::atomic<bool> free_running{false};
  Clock::time_point sent;

 private:
  std::size_t i_ = 0;
};

/** Counts frames; wakes its waiter (one at a time) only at the count it waits for: a wake per frame
 *  would put the bench's thread on a core the graph's groups use, every frame (two groups on two cores). */
class FrameSink : public Node {
 public:
  static Manifest manifest() { return Manifest().input<Image>("image"); }
  void process() override {
    std::lock_guard<std::mutex> l(m);
    ++count;
    last = Clock::now();
    if (count == wanted) cv.notify_all();
  }
  void waitFor(long n) {
    std::unique_lock<std::mutex> l(m);
    wanted = n;
    cv.wait(l, [&] { return count >= n; });
  }
  long seen() {
    std::lock_guard<std::mutex> l(m);
    return count;
  }
  std::mutex m;
  std::condition_variable cv;
  long count = 0, wanted = 0;
  Clock::time_point last;
};

/** A stage of a generated chain: `us` microseconds of busy work, then the frame passed on. */
class Work : public Node {
 public:
  static Manifest manifest() { return Manifest().input<Any>("in").output<Any>("out"); }
  void process() override {
    const auto end = Clock::now() + std::chrono::microseconds(us);
    while (Clock::now() < end) {
    }
    publishMessage("out", inputMessage("in"));
  }
  int us = 0;
};

NodeRegistry& registry() {
  return apex_bench::pluginRegistry([](NodeRegistry& r) {
    (void)r.add<FrameSource>("bench/FrameSource");
    (void)r.add<FrameSink>("bench/FrameSink");
    (void)r.add<Work>("bench/Work");
  });
}

/** The chain as an APEX graph; with two groups the second starts at morphology. */
void build(Graph& g, bool two_groups) {
  const std::string b = two_groups ? "second" : "";
  auto add = [&](const std::string& type, const std::string& name, const std::string& group) {
    if (auto r = g.addNode(type, name, group); !r) std::fprintf(stderr, "%s\n", r.message().c_str());
  };
  add("bench/FrameSource", "src", "");
  add("apex_nodes/Rotate", "rotate", "");
  add("apex_nodes/ColorConvert", "gray", "");
  add("apex_nodes/AdaptiveThreshold", "threshold", "");
  add("apex_nodes/Morphology", "morphology", b);
  add("apex_nodes/BlobDetection", "blobs", b);
  add("apex_nodes/Relay", "hold", b);  // frees rotate at once: the overlay's frame waits here
  add("apex_nodes/DrawRegions", "overlay", b);
  add("bench/FrameSink", "sink", b);
  (void)g.setParameter("rotate", "angle", std::to_string(kAngle));
  (void)g.setParameter("threshold", "threshold_type", "binary_inv");
  (void)g.setParameter("blobs", "min_area", "50");
  for (auto [a, ap, c, cp] : std::vector<std::array<std::string, 4>>{{"src", "image", "rotate", "image"},
                                                                     {"rotate", "image", "gray", "image"},
                                                                     {"gray", "image", "threshold", "image"},
                                                                     {"threshold", "image", "morphology", "image"},
                                                                     {"morphology", "image", "blobs", "image"},
                                                                     {"rotate", "image", "hold", "in"},
                                                                     {"hold", "out", "overlay", "image"},
                                                                     {"blobs", "regions", "overlay", "regions"},
                                                                     {"overlay", "image", "sink", "image"}})
    if (auto st = g.connect(a, ap, c, cp); !st) std::fprintf(stderr, "%s\n", st.message().c_str());
}

/** Frames per second with the source always ready: n frames at the sink, after 5 to fill the pipeline. */
double freeRunFps(FrameSource* src, FrameSink* sink, int n) {
  const long at = sink->seen();
  src->free_running = true;
  src->notifyNewData();
  sink->waitFor(at + 5);
  const auto t0 = Clock::now();
  sink->waitFor(at + 5 + n);
  const double fps = n / std::chrono::duration<double>(Clock::now() - t0).count();
  src->free_running = false;
  return fps;
}

struct Figures {
  double latency_ms, fps;
};

Figures apexRun(bool two_groups, const std::vector<cv::Mat>& input, int n) {
  Graph g(registry());
  build(g, two_groups);
  auto* src = static_cast<FrameSource*>(g.nodeObject("src"));
  auto* sink = static_cast<FrameSink*>(g.nodeObject("sink"));
  src->frames = &input;
  g.start();
  (void)g.waitIdle(5);
  double total = 0;
  for (int i = 1; i <= n; ++i) {  // latency: one frame in flight
    src->notifyNewData();
    sink->waitFor(i);
    if (i > 5) total += std::chrono::duration<double, std::milli>(sink->last - src->sent).count();
  }
  const double fps = freeRunFps(src, sink, n);  // throughput: a frame whenever the source's output is free
  g.stop();
  return {total / (n - 5), fps};
}

Figures loopRun(const std::vector<cv::Mat>& input, int n) {
  Loop loop;
  for (int i = 0; i < 5; ++i) loop.run(input[i % input.size()]);
  const auto t0 = Clock::now();
  for (int i = 0; i < n; ++i) loop.run(input[i % input.size()]);
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  return {1000 * s / n, n / s};
}

// ------------------------------------------------------------------ balance

using Groups = std::map<std::string, std::string>;  // node -> thread group

/** What balance proposes for two cores after n frames in the groups the graph has now, with trials
 *  of its closest proposals (n frames each). */
Groups balanced(Graph& g, FrameSource* src, FrameSink* sink, int n, std::string* text = nullptr) {
  const auto before = g.nodeStats();
  (void)freeRunFps(src, sink, n);
  (void)g.waitIdle(5);
  const BalanceInput in = balanceInput(g, measuredTimes(before, g.nodeStats()));
  BalanceOptions options;
  options.groups = 2;
  auto p = balance(in, options);
  if (!p) std::fprintf(stderr, "balance: %s\n", p.message().c_str());
  if (!p) return {};
  // as ~balance with trials: the closest proposals run n frames each, the fastest kept
  TrialOptions trial;
  trial.frames = n;
  src->free_running = true;  // frames always available, as in the measurement
  src->notifyNewData();
  auto trials = tryCandidates(g, in, options, 4, trial);
  src->free_running = false;
  if (!trials) std::fprintf(stderr, "balance trials: %s\n", trials.message().c_str());
  std::string tried;
  if (trials && !trials->fps.empty()) {
    for (std::size_t k = 0; k < trials->fps.size(); ++k) {
      const Proposal& c = trials->candidates[k];
      std::string last;  // the last node of the first stage: where it cuts
      for (std::size_t x : c.order)
        if (c.stage[x] == 0) last = in.nodes[x].name;
      char b[128];
      std::snprintf(b, sizeof b, "%s after %s %.1f (expected %.2f ms per frame)", k ? "," : "; trials (frames/s):", last.c_str(),
                    trials->fps[k], c.period_ns * 1e-6);
      tried += b;
    }
    p = std::move(trials->candidates[trials->fastest]);
  }
  const auto names = stageGroupNames(p.value(), currentGroups(g, in));
  if (text) *text = describeProposal(p.value(), in, names) + tried;
  for (const auto& note : p->notes)
    if (text) *text += "; " + note;
  return placementOf(p.value(), in, names);
}

void place(Graph& g, const Groups& groups) {
  for (const auto& [node, group] : groups)
    if (auto st = g.setThreadGroup(node, group); !st) std::fprintf(stderr, "%s\n", st.message().c_str());
}

/** The demo chain's frames/s in `groups` (node -> group; none: one group), or, with `by_balance`,
 *  in what balance proposes after n frames in one group (its description into *text). */
double demoFps(const std::vector<cv::Mat>& input, int n, const Groups& groups, bool by_balance, std::string* text = nullptr,
               Groups* proposed = nullptr) {
  Graph g(registry());
  build(g, false);
  auto* src = static_cast<FrameSource*>(g.nodeObject("src"));
  auto* sink = static_cast<FrameSink*>(g.nodeObject("sink"));
  src->frames = &input;
  place(g, groups);
  g.start();
  (void)g.waitIdle(5);
  if (by_balance) {
    const Groups chosen = balanced(g, src, sink, n, text);
    place(g, chosen);
    if (proposed) *proposed = chosen;
  }
  const double fps = freeRunFps(src, sink, n);
  g.stop();
  return fps;
}

/** src -> one Work per entry of `us` -> sink; node names in chain order. */
std::vector<std::string> buildChain(Graph& g, const std::vector<int>& us) {
  std::vector<std::string> names{"src"};
  (void)g.addNode("bench/FrameSource", "src");
  for (std::size_t i = 0; i < us.size(); ++i) {
    names.push_back("w" + std::to_string(i));
    (void)g.addNode("bench/Work", names.back());
    static_cast<Work*>(g.nodeObject(names.back()))->us = us[i];
  }
  names.push_back("sink");
  (void)g.addNode("bench/FrameSink", "sink");
  for (std::size_t i = 1; i < names.size(); ++i)
    if (auto st = g.connect(names[i - 1], i == 1 ? "image" : "out", names[i], i + 1 == names.size() ? "image" : "in"); !st)
      std::fprintf(stderr, "%s\n", st.message().c_str());
  return names;
}

/** A generated chain's frames/s with `groups` (none: measure, and place it as balance proposes, into *proposed). */
double chainFps(const std::vector<int>& us, const Groups& groups, const std::vector<cv::Mat>& input, int n,
                Groups* proposed = nullptr) {
  Graph g(registry());
  buildChain(g, us);
  auto* src = static_cast<FrameSource*>(g.nodeObject("src"));
  auto* sink = static_cast<FrameSink*>(g.nodeObject("sink"));
  src->frames = &input;
  place(g, groups);
  g.start();
  (void)g.waitIdle(5);
  if (proposed) place(g, *proposed = balanced(g, src, sink, n));
  const double fps = freeRunFps(src, sink, n);
  g.stop();
  return fps;
}

/** Where a two-group placement cuts the chain: "after w2", or "none" for one group. */
std::string cutOf(const Groups& groups, const std::vector<std::string>& names) {
  for (std::size_t i = 0; i + 1 < names.size(); ++i)
    if (groups.count(names[i]) && groups.count(names[i + 1]) && groups.at(names[i]) != groups.at(names[i + 1]))
      return "after " + names[i];
  return "none";
}

/** The demo's nodes in the order balance cuts them (its topological order: the Relay after blobs). */
const std::vector<std::string> kDemoOrder{"src", "rotate", "gray", "threshold", "morphology", "blobs", "hold", "overlay", "sink"};

/** Two groups: the nodes after `last` in the second. */
Groups cutAfter(const std::string& last) {
  Groups g;
  bool second = false;
  for (const auto& name : kDemoOrder) {
    g[name] = second ? "second" : "default";
    second = second || name == last;
  }
  return g;
}

/** Two copies of the demo chain, one group each, side by side (each its own frames): their frames/s
 *  summed: what two cores give this chain with no pipeline at all, the host's load and shared caches and
 *  memory included. A placement near it fills both cores (one may pass it: each stage's data then fits
 *  its core's cache better than the whole chain's). */
double twoCopiesFps(const std::vector<cv::Mat>& input, int n) {
  std::vector<cv::Mat> own;
  for (const cv::Mat& m : input) own.push_back(m.clone());
  Graph a(registry()), b(registry());
  Graph* graphs[2] = {&a, &b};
  FrameSource* src[2];
  FrameSink* sink[2];
  for (int k = 0; k < 2; ++k) {
    build(*graphs[k], false);
    src[k] = static_cast<FrameSource*>(graphs[k]->nodeObject("src"));
    sink[k] = static_cast<FrameSink*>(graphs[k]->nodeObject("sink"));
    src[k]->frames = k ? &own : &input;
    graphs[k]->start();
    (void)graphs[k]->waitIdle(5);
  }
  for (int k = 0; k < 2; ++k) src[k]->free_running = true, src[k]->notifyNewData();
  for (int k = 0; k < 2; ++k) sink[k]->waitFor(5);  // both running
  const long from[2] = {sink[0]->seen(), sink[1]->seen()};
  const auto t0 = Clock::now();
  sink[0]->waitFor(from[0] + n);  // one window for both: the frames each made in it
  const long frames = sink[0]->seen() - from[0] + sink[1]->seen() - from[1];
  const double fps = double(frames) / std::chrono::duration<double>(Clock::now() - t0).count();
  for (int k = 0; k < 2; ++k) src[k]->free_running = false;
  a.stop(), b.stop();
  return fps;
}

void demoBalanceTable(const std::vector<cv::Mat>& input, int n, int reps) {
  cv::setNumThreads(1);
  // one group, then every cut of the order (the hand placement is the cut after threshold)
  std::vector<std::string> cuts{"none"};
  for (std::size_t i = 0; i + 1 < kDemoOrder.size(); ++i) cuts.push_back(kDemoOrder[i]);
  std::vector<Spread> fps(cuts.size());
  Spread bal, copies;
  std::string text;
  Groups proposed;
  for (int r = 0; r < reps; ++r) {
    for (std::size_t c = 0; c < cuts.size(); ++c) fps[c].add(demoFps(input, n, c == 0 ? Groups{} : cutAfter(cuts[c]), false));
    bal.add(demoFps(input, n, {}, true, &text, &proposed));
    copies.add(twoCopiesFps(input, n));
  }
  std::size_t best = 1;
  for (std::size_t c = 2; c < cuts.size(); ++c)
    if (fps[c].median() > fps[best].median()) best = c;
  const double one = fps[0].median();
  std::printf("\n## Balance: the demo chain placed by it\n\n");
  std::printf("The demo chain above with OpenCV at 1 thread (the Relay `hold` takes the rotated frame for the overlay), in\n");
  std::printf("one group, cut into two groups after each node of the order balance uses (the cut by hand is the one after\n");
  std::printf("threshold), and in the groups `balance` proposes for 2 cores after %d frames in one group. Two copies of\n", n);
  std::printf("the chain side by side, one group each, show what two cores give it without a pipeline in this run (the\n");
  std::printf("host's load, shared caches and memory included): a placement near that fills both cores.\n");
  std::printf("Interleaved, %d repetitions: median (min–max) frames/s; ratios of the medians.\n\n", reps);
  std::printf("| placement | frames/s | vs 1 group |\n|---|---|---|\n");
  for (std::size_t c = 0; c < cuts.size(); ++c)
    std::printf("| %s%s | %s | %.2fx |\n", c == 0 ? "1 group" : ("cut after " + cuts[c]).c_str(), c == best ? " (best)" : "",
                fps[c].text("%.1f").c_str(), fps[c].median() / one);
  std::printf("| balance: cut %s | %s | %.2fx |\n", cutOf(proposed, kDemoOrder).c_str(), bal.text("%.1f").c_str(),
              bal.median() / one);
  std::printf("| two copies side by side, one group each (two cores, no pipeline) | %s | %.2fx |\n", copies.text("%.1f").c_str(),
              copies.median() / one);
  std::printf("\nTarget: balance at least 1.85x one group. Balance / best cut: %.3f; balance / two copies: %.3f.\n",
              bal.median() / fps[best].median(), bal.median() / copies.median());
  std::printf("Its last proposal: %s.\n", text.c_str());
}

void chainBalanceTable(const std::vector<cv::Mat>& input, int n, int reps, int chains) {
  std::printf("\n## Balance: generated chains of unequal stages\n\n");
  std::printf("Source → 6 stages of busy work (200–2000 µs each, drawn from seeds 1, 2, ...) → sink. Every placement in\n");
  std::printf("at most 2 groups (one group, and a cut after each node) is run, and so is balance's (measured over %d\n", n);
  std::printf("frames in one group first); interleaved, %d repetitions, medians. Best: the placement of the highest median.\n\n",
              reps);
  std::printf(
      "| chain µs | balance's cut | best cut | balance frames/s | best frames/s | balance / best |\n|---|---|---|---|---|---|\n");
  for (int seed = 1; seed <= chains; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    std::uniform_int_distribution<int> draw(200, 2000);
    std::vector<int> us(6);
    for (int& u : us) u = draw(rng);
    Graph names_only(registry());
    const auto names = buildChain(names_only, us);
    std::vector<Groups> tries{{}};  // one group, then a cut after each node but the sink
    for (std::size_t c = 0; c + 1 < names.size(); ++c) {
      Groups g;
      for (std::size_t i = 0; i < names.size(); ++i) g[names[i]] = i <= c ? "default" : "second";
      tries.push_back(g);
    }
    std::vector<Spread> fps(tries.size());
    Spread bal;
    Groups proposed;
    for (int r = 0; r < reps; ++r) {
      for (std::size_t t = 0; t < tries.size(); ++t) fps[t].add(chainFps(us, tries[t], input, n));
      bal.add(chainFps(us, {}, input, n, &proposed));
    }
    std::size_t best = 0;
    for (std::size_t t = 1; t < tries.size(); ++t)
      if (fps[t].median() > fps[best].median()) best = t;
    std::string chain;
    for (int u : us) chain += (chain.empty() ? "" : " ") + std::to_string(u);
    std::printf("| %s | %s | %s | %s | %s | %.3f |\n", chain.c_str(), cutOf(proposed, names).c_str(),
                cutOf(tries[best], names).c_str(), bal.text("%.1f").c_str(), fps[best].text("%.1f").c_str(),
                bal.median() / fps[best].median());
  }
  std::printf("\nTarget: balance / best at least 0.95.\n");
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string(argv[1]) == "--quick";
  const int n = quick ? 60 : 200;
  const auto input = frames(8);
  const int default_threads = cv::getNumThreads();
  std::printf("## The demo pipeline (Fig. 2 chain), 640x480\n\n");
  std::printf("Rotate 15 degrees (warpAffine) → gray → adaptive threshold (mean, 11) → open 3x3 → connected\n");
  std::printf("components → overlay. Latency: one frame in flight, from the source's firing to the sink's; the\n");
  std::printf("loop's is its time per frame. Throughput: frames always available. %d frames per figure.\n", n);
  std::printf("In two groups the second group starts at the morphology. The overlay needs the rotated frame too:\n");
  std::printf("a Relay in the second group holds it, so rotate is free for the next frame at once (without it the\n");
  std::printf("edge rotate → overlay would serialise the two groups: no queues, by design).\n\n");
  const int reps = quick ? 3 : 5;
  std::printf("Variants interleaved (loop, 1 group, 2 groups, loop, ...), %d repetitions each: median\n", reps);
  std::printf("(min–max); ratios are of the medians.\n\n");
  std::printf(
      "| OpenCV threads | variant | latency ms | vs loop | frames/s | vs loop | vs 1 group |\n|---|---|---|---|---|---|---|\n");
  std::vector<double> apex_latency;
  for (int threads : {1, default_threads}) {
    cv::setNumThreads(threads);
    Spread loop_ms, loop_fps, one_ms, one_fps, two_ms, two_fps;
    for (int r = 0; r < reps; ++r) {
      const Figures loop = loopRun(input, n);
      const Figures one = apexRun(false, input, n);
      const Figures two = apexRun(true, input, n);
      loop_ms.add(loop.latency_ms), loop_fps.add(loop.fps);
      one_ms.add(one.latency_ms), one_fps.add(one.fps);
      two_ms.add(two.latency_ms), two_fps.add(two.fps);
    }
    std::printf("| %d | hand-written loop | %s | 1.000 | %s | 1.00 | |\n", threads, loop_ms.text("%.3f").c_str(),
                loop_fps.text("%.1f").c_str());
    apex_latency.push_back(one_ms.median());
    std::printf("| %d | APEX, 1 group | %s | %.3f | %s | %.2f | 1.00 |\n", threads, one_ms.text("%.3f").c_str(),
                one_ms.median() / loop_ms.median(), one_fps.text("%.1f").c_str(), one_fps.median() / loop_fps.median());
    std::printf("| %d | APEX, 2 groups | %s | %.3f | %s | %.2f | %.2f |\n", threads, two_ms.text("%.3f").c_str(),
                two_ms.median() / loop_ms.median(), two_fps.text("%.1f").c_str(), two_fps.median() / loop_fps.median(),
                two_fps.median() / one_fps.median());
  }
  std::printf("\nTargets: 1-group latency within 2%% of the loop; 2 groups with OpenCV at 1 thread at least 1.6x\n");
  std::printf("the frames/s of 1 group.\n");
  // The nodelet chain ran just before, in this scripts/bench run (its own process: a manager).
  const char* nodelet[] = {std::getenv("APEX_NODELET_LATENCY_1"), std::getenv("APEX_NODELET_LATENCY_DEFAULT")};
  if (nodelet[0] && nodelet[1]) {
    std::printf("\n## Against a chain of nodelets\n\n");
    std::printf("The same chain as minimal nodelets in one manager (bench/nodelet_chain.cpp): sensor_msgs/Image\n");
    std::printf("shared between them, cv_bridge in and out at each stage. Latency per frame, one frame in flight.\n\n");
    std::printf("| OpenCV threads | nodelet chain ms | APEX 1 group ms | APEX / nodelets |\n|---|---|---|---|\n");
    for (int i = 0; i < 2; ++i)
      std::printf("| %s | %.3f | %.3f | %.3f |\n", i == 0 ? "1" : std::to_string(default_threads).c_str(), std::atof(nodelet[i]),
                  apex_latency[i], apex_latency[i] / std::atof(nodelet[i]));
  }
  demoBalanceTable(input, n, reps);
  chainBalanceTable(input, quick ? 60 : 150, quick ? 1 : 3, quick ? 1 : 3);
  return 0;
}
