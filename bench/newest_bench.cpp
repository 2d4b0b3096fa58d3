// The newest frame across thread groups (#54 item 6): a camera-like source gets frames at 80 Hz
// from its own thread (as ROS callbacks come) and keeps only the newest; a slower worker
// (20 ms a frame, busy) takes them. Per firing of the worker: how many newer frames had arrived
// when it started (0: it works on the newest), and the latency from a frame's arrival to the
// worker's end. Variants, interleaved and repeated: worker in the source's group (the baseline),
// in another group with a source that is only driven (SourceMode::Driven: the rule before), and
// in another group with a source that keeps the newest (SourceMode::Newest, what subscribers are).
//   apex_bench_newest [RUNS] [SECONDS]
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "apex/core/graph.hpp"
#include "spread.hpp"

using namespace apex;
using apex_bench::Spread;
using Clock = std::chrono::steady_clock;

namespace {

constexpr double kArrivalHz = 80, kWorkMs = 20;

std::int64_t nowNs() { return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count(); }

struct Frame {
  std::int64_t seq = 0, arrived_ns = 0;
};

/** Frames arrive from outside (arrive()); it keeps the newest. */
struct Camera : Node {
  void arrive(std::int64_t seq) {
    {
      std::lock_guard<std::mutex> lock(m);
      frame = Frame{seq, nowNs()};
    }
    newest.store(seq);
    notifyNewData();
  }
  void process() override {
    std::lock_guard<std::mutex> lock(m);
    publish("out", frame);
  }
  std::mutex m;
  Frame frame;
  std::atomic<std::int64_t> newest{0};
};
struct DrivenCamera : Camera {
  static Manifest manifest() { return Manifest().output<Frame>("out").driven(); }
};
struct NewestCamera : Camera {
  static Manifest manifest() { return Manifest().output<Frame>("out").keepsNewest(); }
};

struct Worker : Node {
  static Manifest manifest() { return Manifest().input<Frame>("in"); }
  void process() override {
    const Frame f = *input<Frame>("in");
    const std::int64_t behind = camera->newest.load() - f.seq;
    const auto until = Clock::now() + std::chrono::duration<double, std::milli>(kWorkMs);
    while (Clock::now() < until) {
    }
    std::lock_guard<std::mutex> lock(m);
    newer.push_back(behind);
    latency_ms.push_back((nowNs() - f.arrived_ns) / 1e6);
  }
  Camera* camera = nullptr;
  std::mutex m;
  std::vector<std::int64_t> newer;
  std::vector<double> latency_ms;
};

NodeRegistry registry() {
  NodeRegistry r;
  (void)r.add<DrivenCamera>("bench/DrivenCamera");
  (void)r.add<NewestCamera>("bench/NewestCamera");
  (void)r.add<Worker>("bench/Worker");
  return r;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * (v.size() - 1))];
}

struct Run {
  double p50 = 0, p95 = 0, newest_pct = 0, behind_p50 = 0;
};

Run run(const char* camera, bool two_groups, double seconds) {
  Graph g(registry());
  (void)g.addNode(camera, "cam");
  (void)g.addNode("bench/Worker", "work", two_groups ? "worker" : "");
  (void)g.connect("cam", "out", "work", "in");
  auto* cam = static_cast<Camera*>(g.nodeObject("cam"));
  auto* work = static_cast<Worker*>(g.nodeObject("work"));
  work->camera = cam;
  g.start();
  const auto period = std::chrono::duration<double>(1.0 / kArrivalHz);
  const auto start = Clock::now();
  for (std::int64_t seq = 1; Clock::now() - start < std::chrono::duration<double>(seconds); ++seq) {
    cam->arrive(seq);
    std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(period * seq));
  }
  g.stop();
  std::lock_guard<std::mutex> lock(work->m);
  Run r;
  const std::size_t skip = std::min<std::size_t>(5, work->latency_ms.size());  // warm-up
  std::vector<double> lat(work->latency_ms.begin() + skip, work->latency_ms.end()), behind;
  for (std::size_t i = skip; i < work->newer.size(); ++i) behind.push_back(static_cast<double>(work->newer[i]));
  r.p50 = percentile(lat, 0.5), r.p95 = percentile(lat, 0.95), r.behind_p50 = percentile(behind, 0.5);
  r.newest_pct = behind.empty() ? 0 : 100.0 * std::count(behind.begin(), behind.end(), 0.0) / behind.size();
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 5;
  const double seconds = argc > 2 ? std::atof(argv[2]) : 3;
  struct Variant {
    const char* name;
    const char* camera;
    bool two_groups;
    Spread p50, p95, newest, behind;
  };
  std::vector<Variant> variants = {{"one group (baseline)", "bench/NewestCamera", false, {}, {}, {}, {}},
                                   {"two groups, driven source (the rule before)", "bench/DrivenCamera", true, {}, {}, {}, {}},
                                   {"two groups, source keeping the newest", "bench/NewestCamera", true, {}, {}, {}, {}}};
  for (int i = 0; i < runs; ++i)
    for (auto& v : variants) {
      const Run r = run(v.camera, v.two_groups, seconds);
      v.p50.add(r.p50), v.p95.add(r.p95), v.newest.add(r.newest_pct), v.behind.add(r.behind_p50);
    }
  std::printf(
      "| variant | latency p50, ms | latency p95, ms | firings on the newest frame, %% | newer frames at the start, p50 | p50 / "
      "one group |\n");
  std::printf("|---|---|---|---|---|---|\n");
  const double base = variants[0].p50.median();
  for (auto& v : variants)
    std::printf("| %s | %s | %s | %s | %s | %.2fx |\n", v.name, v.p50.text("%.1f").c_str(), v.p95.text("%.1f").c_str(),
                v.newest.text("%.0f").c_str(), v.behind.text("%.0f").c_str(), v.p50.median() / base);
  return 0;
}
