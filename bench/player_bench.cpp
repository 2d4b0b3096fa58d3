// The bag player: seek time on a 10,000-frame bag (to the first frame against
// the last), and the time from a parameter change to the new result on a held
// frame against the pipeline's own processing of that frame (a seek to it),
// measured interleaved in the same run.
//   apex_bench_player [--quick]   (with the devel space sourced: node types come from pluginlib)
#include <cv_bridge/cv_bridge.h>
#include <rosbag/bag.h>
#include <unistd.h>

#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "apex/core/graph.hpp"
#include "apex_nodes/types.hpp"
#include "plugin_registry.hpp"
#include "spread.hpp"

using namespace apex;
using Clock = std::chrono::steady_clock;
using apex_bench::Spread;

namespace {

/** Counts results; the bench waits for the next one. */
class ResultSink : public Node {
 public:
  static Manifest manifest() { return Manifest().input<Any>("in"); }
  void process() override {
    std::lock_guard<std::mutex> l(m);
    ++count;
    last = Clock::now();
    cv.notify_all();
  }
  /** Runs `act` and returns the ms until the next result. */
  template <class F>
  double timed(F act) {
    long before;
    {
      std::lock_guard<std::mutex> l(m);
      before = count;
    }
    const auto t0 = Clock::now();
    act();
    std::unique_lock<std::mutex> l(m);
    cv.wait(l, [&] { return count > before; });
    return std::chrono::duration<double, std::milli>(last - t0).count();
  }
  std::mutex m;
  std::condition_variable cv;
  long count = 0;
  Clock::time_point last;
};

NodeRegistry& registry() {
  return apex_bench::pluginRegistry([](NodeRegistry& r) { (void)r.add<ResultSink>("bench/ResultSink"); });
}

/** A bag of `n` frames of `cols` x `rows` with dark squares, on /camera/image_raw at 10 Hz. */
std::string writeBag(const std::string& path, int n, int cols, int rows) {
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  cv::RNG rng(7);
  std_msgs::Header h;
  h.frame_id = "camera";
  for (int i = 0; i < n; ++i) {
    cv::Mat m(rows, cols, CV_8UC3);
    rng.fill(m, cv::RNG::UNIFORM, 150, 220);
    for (int k = 0; k < 4 && cols > 200; ++k)
      cv::rectangle(m, cv::Rect(rng.uniform(20, cols - 120), rng.uniform(20, rows - 120), 80, 80), cv::Scalar::all(30),
                    cv::FILLED);
    h.stamp = ros::Time(1000) + ros::Duration(0.1 * i);
    bag.write("/camera/image_raw", h.stamp, cv_bridge::CvImage(h, "bgr8", m).toImageMsg());
  }
  return path;
}

void check(const Status& st) {
  if (!st) std::fprintf(stderr, "%s\n", st.message().c_str());
}

void addPlayer(Graph& g, const std::string& bag) {
  NodeDescription d;
  d.name = "bag", d.type = "apex_nodes/BagReader";
  d.parameters = {{"file", bag}, {"topics", "[/camera/image_raw]"}, {"playing", "false"}};
  check(g.addNode(d).status());
}

double p95(const Spread& s) {
  auto v = s.v;
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[std::min(v.size() - 1, v.size() * 95 / 100)];
}

void seekTable(const std::string& bag, int reps) {
  Graph g(registry());
  addPlayer(g, bag);
  check(g.addNode("bench/ResultSink", "sink").status());
  check(g.connect("bag", "camera_image_raw", "sink", "in"));
  g.start();
  auto* sink = static_cast<ResultSink*>(g.nodeObject("sink"));
  Spread first, last;
  for (int r = 0; r < reps; ++r) {  // interleaved
    first.add(sink->timed([&] { check(g.setParameter("bag", "frame", "0").status()); }));
    last.add(sink->timed([&] { check(g.setParameter("bag", "frame", "9999").status()); }));
  }
  g.stop();
  std::printf("## Seeking in a bag of 10,000 frames\n\n");
  std::printf("BagReader paused; `frame` set, alternately to the first and the last frame, %d times each;\n", reps);
  std::printf("time until that frame (64 x 48 pixels) arrives at a sink. A player that replayed from the start\n");
  std::printf("would take about 10,000 times longer for the last.\n\n");
  std::printf("| seek to | ms: median (min–max) | vs first |\n|---|---|---|\n");
  std::printf("| frame 0 | %s | 1.00 |\n", first.text("%.3f").c_str());
  std::printf("| frame 9999 | %s | %.2f |\n\n", last.text("%.3f").c_str(), last.median() / first.median());
}

void heldFrameTable(const std::string& bag, int reps) {
  Graph g(registry());
  addPlayer(g, bag);
  for (auto [type, name] : std::vector<std::pair<std::string, std::string>>{{"apex_nodes/Rotate", "rotate"},
                                                                            {"apex_nodes/ColorConvert", "gray"},
                                                                            {"apex_nodes/AdaptiveThreshold", "threshold"},
                                                                            {"apex_nodes/Morphology", "morphology"},
                                                                            {"apex_nodes/BlobDetection", "blobs"},
                                                                            {"apex_nodes/DrawRegions", "overlay"},
                                                                            {"bench/ResultSink", "sink"}})
    check(g.addNode(type, name).status());
  check(g.setParameter("threshold", "threshold_type", "binary_inv").status());
  check(g.setParameter("threshold", "block_size", "101").status());
  check(g.setParameter("threshold", "method", "gaussian").status());
  for (auto [a, ap, c, cp] : std::vector<std::array<std::string, 4>>{{"bag", "camera_image_raw", "rotate", "image"},
                                                                     {"rotate", "image", "gray", "image"},
                                                                     {"gray", "image", "threshold", "image"},
                                                                     {"threshold", "image", "morphology", "image"},
                                                                     {"morphology", "image", "blobs", "image"},
                                                                     {"rotate", "image", "overlay", "image"},
                                                                     {"blobs", "regions", "overlay", "regions"},
                                                                     {"overlay", "image", "sink", "in"}})
    check(g.connect(a, ap, c, cp));
  g.start();
  auto* sink = static_cast<ResultSink*>(g.nodeObject("sink"));
  sink->timed([&] { check(g.setParameter("bag", "frame", "7").status()); });
  Spread seek, change;
  for (int r = 0; r < reps; ++r) {  // interleaved; spaced beyond the re-run interval (40 ms): each change runs at once
    seek.add(sink->timed([&] { check(g.setParameter("bag", "frame", "7").status()); }));
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
    change.add(sink->timed([&] { check(g.setParameter("threshold", "c", r % 2 ? "20" : "25").status()); }));
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
  }
  g.stop();
  std::printf("## From a parameter change to the new result on a held frame\n\n");
  std::printf("The camera chain (rotate, gray, adaptive threshold 101 x 101 gaussian, morphology, blobs, overlay) on\n");
  std::printf("a paused BagReader's frame 7 (640 x 480); %d times, interleaved: set `frame` to 7 (the pipeline's\n", reps);
  std::printf("own processing of the frame, read from the bag), then set the threshold's `c` (the held frame runs\n");
  std::printf("again by itself). Time until the overlay arrives at a sink.\n\n");
  std::printf("| | ms: median (min–max) | p95 | vs the pipeline |\n|---|---|---|---|\n");
  std::printf("| seek to frame 7 (the pipeline) | %s | %.2f | 1.00 |\n", seek.text("%.2f").c_str(), p95(seek));
  std::printf("| set threshold/c | %s | %.2f | %.2f |\n\n", change.text("%.2f").c_str(), p95(change),
              change.median() / seek.median());
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  ros::Time::init();
  const auto dir = std::filesystem::temp_directory_path() / ("apex_bench_player_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  seekTable(writeBag((dir / "seek.bag").string(), 10000, 64, 48), quick ? 10 : 50);
  heldFrameTable(writeBag((dir / "chain.bag").string(), 40, 640, 480), quick ? 10 : 100);
  std::filesystem::remove_all(dir);
  return 0;
}
