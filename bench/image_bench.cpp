// The image library's nodes, each alone, against the OpenCV call it makes, written by hand in a
// plain loop with the same parameters and a reused output: what a node adds to its call (input
// checks, parameter reads, its output buffer, taking and delivering messages). On real 640x480
// images from opencv-doc, OpenCV at one thread for both.
//   apex_bench_images [--quick]   (with the devel space sourced: node types come from pluginlib)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <functional>
#include <mutex>
#include <opencv2/core/utility.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/background_segm.hpp>
#include <string>
#include <utility>
#include <vector>

#include "apex/core/graph.hpp"
#include "apex_nodes/features.hpp"
#include "apex_nodes/shapes.hpp"
#include "apex_nodes/types.hpp"
#include "plugin_registry.hpp"
#include "spread.hpp"

using namespace apex;
using apex_bench::Spread;
using apex_nodes::Image;
using Clock = std::chrono::steady_clock;

namespace {

const std::string kData = "/usr/share/doc/opencv-doc/examples/data";  // scripts/install_deps installs opencv-doc
constexpr double kAngle = 15 * M_PI / 180;  // Rotate's any-angle case (warpAffine), as in the pipeline bench

/** Sends the frame it is given, once per notifyNewData. */
class ImageSource : public Node {
 public:
  static Manifest manifest() { return Manifest().output<Image>("image").driven(); }
  void process() override { publish<Image>("image", next); }
  std::shared_ptr<const Image> next;
};

/** Counts what arrives (Nothing too: a node that fails sends it) and drops it at once, so the
 *  node's output buffer is free again for the next frame. */
class SinkBase : public Node {
 public:
  void process() override {
    std::lock_guard<std::mutex> l(m_);
    ++count_;
    cv_.notify_all();
  }
  /** False if the n-th message has not come within 30 s. */
  bool waitFor(long n) {
    std::unique_lock<std::mutex> l(m_);
    return cv_.wait_for(l, std::chrono::seconds(30), [&] { return count_ >= n; });
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  long count_ = 0;
};

template <class T>
class Sink : public SinkBase {
 public:
  static Manifest manifest() { return Manifest().optionalInput<T>("in"); }
};

NodeRegistry& registry() {
  return apex_bench::pluginRegistry([](NodeRegistry& r) {
    (void)r.add<ImageSource>("bench/ImageSource");
    (void)r.add<Sink<Image>>("bench/ImageSink");
    (void)r.add<Sink<apex_nodes::Contours>>("bench/ContoursSink");
    (void)r.add<Sink<apex_nodes::Lines>>("bench/LinesSink");
    (void)r.add<Sink<apex_nodes::Circles>>("bench/CirclesSink");
    (void)r.add<Sink<apex_nodes::Keypoints>>("bench/KeypointsSink");
  });
}

using Params = std::vector<std::pair<std::string, std::string>>;

/** One node type on one kind of input, and the OpenCV call it stands for. */
struct Case {
  std::string label;  ///< the row's name: the type's, or with the variant ("Rotate 15°")
  std::string type;  ///< e.g. "apex_nodes/GaussianBlur"
  std::string input;  ///< what it is fed, in words
  std::vector<std::shared_ptr<const Image>> frames;  ///< fed in turn (one for most)
  Params params;
  std::string out_port;
  std::string sink;  ///< the bench's sink type for the output's message type
  std::string call_text;  ///< the call in words
  std::function<void(const cv::Mat&)> call;  ///< the call, keeping its outputs between frames
};

/** Source → the node → sink in one thread group, one frame in flight. */
class NodeRun {
 public:
  explicit NodeRun(const Case& c) {
    auto check = [this](const Status& s) {
      if (!s && error.empty()) error = s.message();
    };
    check(g_.addNode("bench/ImageSource", "src").status());
    check(g_.addNode(c.type, "node").status());
    check(g_.addNode(c.sink, "sink").status());
    for (const auto& [p, v] : c.params) check(g_.setParameter("node", p, v).status());
    check(g_.connect("src", "image", "node", "image"));
    check(g_.connect("node", c.out_port, "sink", "in"));
    if (!error.empty()) return;
    src_ = static_cast<ImageSource*>(g_.nodeObject("src"));
    sink_ = static_cast<SinkBase*>(g_.nodeObject("sink"));
    g_.start();
  }
  ~NodeRun() { g_.stop(); }

  /** Feeds one frame and waits for the node's output at the sink; returns the node's firing
   *  as the runtime timed it (NodeStats::last_ns), µs; or a negative number and `error`. */
  double fire(const std::shared_ptr<const Image>& frame) {
    src_->next = frame;
    src_->notifyNewData();
    if (!sink_->waitFor(++sent_)) {
      error = "no output within 30 s";
      return -1;
    }
    for (const NodeStats& s : g_.nodeStats(3600)) {
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
  Graph g_{registry()};
  ImageSource* src_ = nullptr;
  SinkBase* sink_ = nullptr;
  long sent_ = 0;
  std::uint64_t firings_ = 0;
};

std::shared_ptr<const Image> image(cv::Mat mat, const std::string& encoding) {
  auto i = std::make_shared<Image>();
  i->header.frame_id = "camera";
  i->header.seq = 1;
  i->encoding = encoding;
  i->mat = std::move(mat);
  return i;
}

/** A number as YAML text that reads back as the same double. */
std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

/** The bayer_rggb8 mosaic a camera would have taken of `bgr`: R G / G B in each 2x2 cell. */
cv::Mat mosaic(const cv::Mat& bgr) {
  cv::Mat out(bgr.size(), CV_8UC1);
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x) {
      const cv::Vec3b& p = bgr.at<cv::Vec3b>(y, x);
      out.at<uchar>(y, x) = y % 2 == 0 ? (x % 2 == 0 ? p[2] : p[1]) : (x % 2 == 0 ? p[1] : p[0]);
    }
  return out;
}

/** 640x480 of `m`: its middle if it is large enough, else scaled. */
cv::Mat vga(const cv::Mat& m) {
  if (m.cols >= 640 && m.rows >= 480) return m(cv::Rect((m.cols - 640) / 2, (m.rows - 480) / 2, 640, 480)).clone();
  cv::Mat out;
  cv::resize(m, out, cv::Size(640, 480), 0, 0, cv::INTER_LINEAR);
  return out;
}

std::vector<Case> cases(const cv::Mat& bgr_mat, const cv::Mat& round_mat) {
  using F = std::shared_ptr<const Image>;
  cv::Mat gray_mat, edges_mat, binary_mat, circles_mat;
  cv::cvtColor(bgr_mat, gray_mat, cv::COLOR_BGR2GRAY);
  cv::Canny(gray_mat, edges_mat, 50, 150);
  cv::threshold(gray_mat, binary_mat, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
  cv::cvtColor(round_mat, circles_mat, cv::COLOR_BGR2GRAY);
  cv::medianBlur(circles_mat, circles_mat, 5);  // as HoughCircles wants it
  const F bgr = image(bgr_mat, "bgr8"), gray = image(gray_mat, "mono8"), edges = image(edges_mat, "mono8"),
          binary = image(binary_mat, "mono8"), bayer = image(mosaic(bgr_mat), "bayer_rggb8"),
          circles = image(circles_mat, "mono8");
  // A fixed camera: the background still, a patch of it moving across (8 frames, cycled).
  std::vector<F> moving;
  for (int i = 0; i < 8; ++i) {
    cv::Mat m = bgr_mat.clone();
    bgr_mat(cv::Rect(0, 0, 100, 100)).copyTo(m(cv::Rect(40 + 70 * i, 190, 100, 100)));
    moving.push_back(image(m, "bgr8"));
  }
  const cv::Matx33d warp(1.0, 0.08, -20.0, 0.03, 1.0, -10.0, 0.0001, 0.0002, 1.0);
  const std::string warp_text = "[1.0, 0.08, -20.0, 0.03, 1.0, -10.0, 0.0001, 0.0002, 1.0]";
  const cv::Mat rotation = cv::getRotationMatrix2D(cv::Point2f(320, 240), kAngle * 180.0 / M_PI, 1.0);
  const cv::Mat kernel3 = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
  const std::string sink = "bench/ImageSink";
  auto filter = [&](const char* name, const F& in, const char* input, Params p, const char* text,
                    std::function<void(const cv::Mat&, cv::Mat&)> f, const char* label = nullptr,
                    const char* out_port = "image") {
    return Case{label ? label : name,
                std::string("apex_nodes/") + name,
                input,
                {in},
                std::move(p),
                out_port,
                sink,
                text,
                [f = std::move(f), out = cv::Mat()](const cv::Mat& m) mutable { f(m, out); }};
  };
  std::vector<Case> c;
  c.push_back(filter("GaussianBlur", bgr, "bgr8", {{"kernel_size", "5"}, {"sigma", "0"}}, "GaussianBlur 5x5",
                     [](const cv::Mat& in, cv::Mat& out) { cv::GaussianBlur(in, out, cv::Size(5, 5), 0); }));
  c.push_back(filter("MedianBlur", bgr, "bgr8", {{"ksize", "5"}}, "medianBlur 5",
                     [](const cv::Mat& in, cv::Mat& out) { cv::medianBlur(in, out, 5); }));
  c.push_back(filter("BilateralFilter", bgr, "bgr8", {{"d", "5"}, {"sigma_color", "75"}, {"sigma_space", "75"}},
                     "bilateralFilter d 5, 75, 75",
                     [](const cv::Mat& in, cv::Mat& out) { cv::bilateralFilter(in, out, 5, 75, 75, cv::BORDER_REFLECT_101); }));
  c.push_back(filter("BoxFilter", bgr, "bgr8", {{"ksize", "5"}, {"normalize", "true"}}, "boxFilter 5x5",
                     [](const cv::Mat& in, cv::Mat& out) {
                       cv::boxFilter(in, out, -1, cv::Size(5, 5), cv::Point(-1, -1), true, cv::BORDER_REFLECT_101);
                     }));
  c.push_back(filter("Sobel", gray, "mono8", {{"dx", "1"}, {"dy", "0"}, {"ksize", "3"}, {"ddepth", "16S"}},
                     "Sobel dx 1, 3x3, to 16S",
                     [](const cv::Mat& in, cv::Mat& out) { cv::Sobel(in, out, CV_16S, 1, 0, 3, 1, 0, cv::BORDER_REFLECT_101); }));
  c.push_back(filter("Scharr", gray, "mono8", {{"dx", "1"}, {"dy", "0"}, {"ddepth", "16S"}}, "Scharr dx 1, to 16S",
                     [](const cv::Mat& in, cv::Mat& out) { cv::Scharr(in, out, CV_16S, 1, 0, 1, 0, cv::BORDER_REFLECT_101); }));
  c.push_back(filter("Laplacian", gray, "mono8", {{"ksize", "1"}, {"ddepth", "16S"}}, "Laplacian 3x3, to 16S",
                     [](const cv::Mat& in, cv::Mat& out) { cv::Laplacian(in, out, CV_16S, 1, 1, 0, cv::BORDER_REFLECT_101); }));
  c.push_back(filter(
      "Canny", gray, "mono8", {{"threshold1", "50"}, {"threshold2", "150"}}, "Canny 50, 150",
      [](const cv::Mat& in, cv::Mat& out) { cv::Canny(in, out, 50, 150, 3, false); }, nullptr, "edges"));
  c.push_back(filter("Threshold", gray, "mono8", {{"threshold", "128"}, {"max_value", "255"}, {"type", "binary"}},
                     "threshold 128, binary",
                     [](const cv::Mat& in, cv::Mat& out) { cv::threshold(in, out, 128, 255, cv::THRESH_BINARY); }));
  c.push_back(filter("AdaptiveThreshold", gray, "mono8",
                     {{"max_value", "255"}, {"method", "mean"}, {"threshold_type", "binary"}, {"block_size", "11"}, {"c", "2"}},
                     "adaptiveThreshold mean, 11, 2", [](const cv::Mat& in, cv::Mat& out) {
                       cv::adaptiveThreshold(in, out, 255, cv::ADAPTIVE_THRESH_MEAN_C, cv::THRESH_BINARY, 11, 2);
                     }));
  c.push_back(filter(
      "Morphology", binary, "binary mono8", {{"operation", "open"}, {"shape", "rect"}, {"kernel_size", "3"}, {"iterations", "1"}},
      "morphologyEx open, rect 3x3",
      [kernel3](const cv::Mat& in, cv::Mat& out) { cv::morphologyEx(in, out, cv::MORPH_OPEN, kernel3, cv::Point(-1, -1), 1); }));
  c.push_back(filter("EqualizeHist", gray, "mono8", {}, "equalizeHist",
                     [](const cv::Mat& in, cv::Mat& out) { cv::equalizeHist(in, out); }));
  c.push_back(filter("CLAHE", gray, "mono8", {{"clip_limit", "2"}, {"tile_grid_size", "8"}}, "CLAHE 2, 8x8 tiles",
                     [clahe = cv::createCLAHE(2.0, cv::Size(8, 8))](const cv::Mat& in, cv::Mat& out) { clahe->apply(in, out); }));
  c.push_back(filter("Normalize", gray, "mono8", {{"alpha", "0"}, {"beta", "255"}, {"norm_type", "minmax"}, {"dtype", "same"}},
                     "normalize minmax 0..255",
                     [](const cv::Mat& in, cv::Mat& out) { cv::normalize(in, out, 0, 255, cv::NORM_MINMAX, CV_8U); }));
  c.push_back(filter("ConvertScale", gray, "mono8", {{"alpha", "0.5"}, {"beta", "10"}, {"rtype", "32F"}},
                     "convertTo 32F, 0.5 x + 10", [](const cv::Mat& in, cv::Mat& out) { in.convertTo(out, CV_32F, 0.5, 10); }));
  c.push_back(filter("Flip", bgr, "bgr8", {{"flip_code", "horizontal"}}, "flip 1",
                     [](const cv::Mat& in, cv::Mat& out) { cv::flip(in, out, 1); }));
  c.push_back(filter("PyrDown", bgr, "bgr8", {}, "pyrDown", [](const cv::Mat& in, cv::Mat& out) { cv::pyrDown(in, out); }));
  c.push_back(filter("PyrUp", bgr, "bgr8", {}, "pyrUp", [](const cv::Mat& in, cv::Mat& out) { cv::pyrUp(in, out); }));
  c.push_back(filter("Resize", bgr, "bgr8", {{"scale", "0.5"}, {"interpolation", "area"}}, "resize 0.5, area",
                     [](const cv::Mat& in, cv::Mat& out) { cv::resize(in, out, cv::Size(), 0.5, 0.5, cv::INTER_AREA); }));
  c.push_back(filter(
      "Rotate", bgr, "bgr8", {{"angle", num(kAngle)}}, "warpAffine 15°",
      [rotation](const cv::Mat& in, cv::Mat& out) { cv::warpAffine(in, out, rotation, in.size()); }, "Rotate 15°"));
  c.push_back(filter(
      "Rotate", bgr, "bgr8", {{"angle", num(M_PI / 2)}}, "rotate 90° ccw",
      [](const cv::Mat& in, cv::Mat& out) { cv::rotate(in, out, cv::ROTATE_90_COUNTERCLOCKWISE); }, "Rotate 90°"));
  c.push_back(filter("WarpPerspective", bgr, "bgr8",
                     {{"m", warp_text}, {"interpolation", "linear"}, {"border_mode", "constant"}, {"inverse_map", "false"}},
                     "warpPerspective linear", [warp](const cv::Mat& in, cv::Mat& out) {
                       cv::warpPerspective(in, out, warp, in.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT);
                     }));
  c.push_back(
      filter("DistanceTransform", binary, "binary mono8", {{"distance_type", "l2"}}, "distanceTransform L2, 3x3",
             [](const cv::Mat& in, cv::Mat& out) { cv::distanceTransform(in, out, cv::DIST_L2, cv::DIST_MASK_3, CV_32F); }));
  c.push_back(filter("ColorConvert", bgr, "bgr8", {{"conversion", "BGR2GRAY"}}, "cvtColor BGR2GRAY",
                     [](const cv::Mat& in, cv::Mat& out) { cv::cvtColor(in, out, cv::COLOR_BGR2GRAY); }));
  c.push_back(filter(
      "ColorRange", bgr, "bgr8", {{"color_space", "hsv"}, {"lower", "[0, 150, 100]"}, {"upper", "[179, 255, 255]"}},
      "cvtColor BGR2HSV, inRange",
      [hsv = cv::Mat()](const cv::Mat& in, cv::Mat& out) mutable {
        cv::cvtColor(in, hsv, cv::COLOR_BGR2HSV);
        cv::inRange(hsv, cv::Scalar(0, 150, 100), cv::Scalar(179, 255, 255), out);
      },
      nullptr, "mask"));
  c.push_back(filter("Debayer", bayer, "bayer_rggb8", {{"method", "bilinear"}}, "cvtColor BayerRGGB2BGR",
                     [](const cv::Mat& in, cv::Mat& out) { cv::cvtColor(in, out, cv::COLOR_BayerRGGB2BGR); }));

  c.push_back(
      Case{"FindContours",
           "apex_nodes/FindContours",
           "Canny edges",
           {edges},
           {{"mode", "list"}, {"method", "simple"}},
           "contours",
           "bench/ContoursSink",
           "findContours list, simple",
           [contours = std::vector<std::vector<cv::Point>>(), hierarchy = std::vector<cv::Vec4i>()](const cv::Mat& in) mutable {
             cv::findContours(in, contours, hierarchy, cv::RETR_LIST, cv::CHAIN_APPROX_SIMPLE);
           }});
  c.push_back(Case{"HoughLines",
                   "apex_nodes/HoughLines",
                   "Canny edges",
                   {edges},
                   {{"rho", "1"}, {"theta", "1"}, {"threshold", "50"}, {"min_line_length", "50"}, {"max_line_gap", "10"}},
                   "lines",
                   "bench/LinesSink",
                   "HoughLinesP 1, 1°, 50, 50, 10",
                   [lines = std::vector<cv::Vec4i>()](const cv::Mat& in) mutable {
                     cv::HoughLinesP(in, lines, 1, 1 * CV_PI / 180, 50, 50, 10);
                   }});
  c.push_back(Case{"HoughCircles",
                   "apex_nodes/HoughCircles",
                   "smarties, gray, median 5",
                   {circles},
                   {{"method", "gradient"},
                    {"dp", "1"},
                    {"min_dist", "20"},
                    {"param1", "100"},
                    {"param2", "30"},
                    {"min_radius", "0"},
                    {"max_radius", "0"}},
                   "circles",
                   "bench/CirclesSink",
                   "HoughCircles gradient 1, 20, 100, 30",
                   [found = std::vector<cv::Vec3f>()](const cv::Mat& in) mutable {
                     cv::HoughCircles(in, found, cv::HOUGH_GRADIENT, 1, 20, 100, 30, 0, 0);
                   }});
  c.push_back(Case{"Keypoints (orb)",
                   "apex_nodes/Keypoints",
                   "mono8",
                   {gray},
                   {{"method", "orb"}, {"max_features", "500"}, {"threshold", "0"}},
                   "keypoints",
                   "bench/KeypointsSink",
                   "ORB 500: detectAndCompute",
                   [orb = cv::ORB::create(500, 1.2f, 8, 31, 0, 2, cv::ORB::HARRIS_SCORE, 31, 20),
                    keypoints = std::vector<cv::KeyPoint>(), descriptors = cv::Mat()](const cv::Mat& in) mutable {
                     orb->detectAndCompute(in, cv::noArray(), keypoints, descriptors);
                   }});
  c.push_back(
      Case{"BackgroundSubtraction (mog2)",
           "apex_nodes/BackgroundSubtraction",
           "8 bgr8 frames, a patch moving",
           moving,
           {{"method", "mog2"}, {"history", "500"}, {"var_threshold", "16"}, {"detect_shadows", "true"}, {"learning_rate", "-1"}},
           "mask",
           "bench/ImageSink",
           "MOG2 500, 16, shadows: apply",
           [mog = cv::createBackgroundSubtractorMOG2(500, 16, true), mask = cv::Mat()](const cv::Mat& in) mutable {
             mog->apply(in, mask, -1);
           }});
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string(argv[1]) == "--quick";
  const int rounds = quick ? 3 : 7, min_frames = quick ? 3 : 5, max_frames = quick ? 30 : 100;
  const double budget_us = quick ? 20e3 : 80e3;  // per block of frames: its frame count follows from the call's time
  cv::setNumThreads(1);

  std::printf("## Image nodes against their OpenCV call, 640x480\n\n");
  const cv::Mat building = cv::imread(kData + "/building.jpg"), smarties = cv::imread(kData + "/smarties.png");
  if (building.empty() || smarties.empty()) {
    std::printf("Not measured: %s/building.jpg or smarties.png cannot be read (opencv-doc, scripts/install_deps).\n",
                kData.c_str());
    return 0;
  }
  const std::vector<Case> all = cases(vga(building), vga(smarties));

  std::printf("Each node type alone (a source → the node → a sink, one thread group, loaded through pluginlib)\n");
  std::printf("against the OpenCV call it makes, written by hand in a plain loop with the same parameters and\n");
  std::printf("its output Mat (or vectors, model) reused from frame to frame. The node's time is its firing as\n");
  std::printf("the runtime clocks it (`NodeStats::last_ns`, one TSC read per firing): taking its input, process()\n");
  std::printf("(checks, parameter reads, its output buffer, the call) and delivering its output; not the source's\n");
  std::printf("hop, nor waking the thread. One frame in flight, frames back to back, so each node's output\n");
  std::printf("buffer is free again and reused. The call's time: steady_clock around each call. Input: the middle\n");
  std::printf("640x480 of opencv-doc's building.jpg (bgr8; mono8 by BGR2GRAY; binary by Otsu; edges by Canny\n");
  std::printf("50, 150; a bayer_rggb8 mosaic sampled from it), smarties.png scaled to 640x480 for HoughCircles.\n");
  std::printf("OpenCV at one thread (cv::setNumThreads(1)) for both. Interleaved in %d rounds (node, call, node,\n", rounds);
  std::printf("call, ...), each of N frames per side (N from the call's time, %d to %d); a round's figure is the\n", min_frames,
              max_frames);
  std::printf("median of its frames; median (min–max) over the rounds, µs; the ratio is per round. Goal: node ≤\n");
  std::printf("call × 1.05 + 20 µs (medians).\n\n");
  std::printf("| node | input | OpenCV call | frames × rounds | call µs | node µs | node / call | within goal |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");

  std::vector<std::string> outside, failed;
  for (const Case& c : all) {
    NodeRun node(c);
    std::size_t next_node = 0, next_call = 0;
    auto fireNode = [&] { return node.fire(c.frames[next_node++ % c.frames.size()]); };
    auto fireCall = [&] {
      const cv::Mat& m = c.frames[next_call++ % c.frames.size()]->mat;
      const auto t0 = Clock::now();
      c.call(m);
      return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
    };
    double call_us = 0;
    for (int i = 0; i < 5 && node.error.empty(); ++i) {  // warm up: first allocations, models, caches
      fireNode();
      call_us = fireCall();
    }
    if (!node.error.empty()) {
      std::printf("| %s | %s | %s | | | | | failed: %s |\n", c.label.c_str(), c.input.c_str(), c.call_text.c_str(),
                  node.error.c_str());
      failed.push_back(c.label);
      continue;
    }
    const int n = std::clamp(static_cast<int>(budget_us / std::max(call_us, 1.0)), min_frames, max_frames);
    Spread call, nodes, ratio;
    for (int r = 0; r < rounds && node.error.empty(); ++r) {
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
      continue;
    }
    const bool within = nodes.median() <= call.median() * 1.05 + 20;
    if (!within) outside.push_back(c.label);
    const char* fmt = call.median() < 100 ? "%.1f" : "%.0f";
    std::printf("| %s | %s | %s | %d × %d | %s | %s | %.2fx (%.2f–%.2f) | %s |\n", c.label.c_str(), c.input.c_str(),
                c.call_text.c_str(), n, rounds, call.text(fmt).c_str(), nodes.text(fmt).c_str(), ratio.median(), ratio.min(),
                ratio.max(), within ? "yes" : "no");
  }
  auto list = [](const std::vector<std::string>& names) {
    std::string s;
    for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
    return s;
  };
  std::printf("\n%s\n", outside.empty() && failed.empty()
                            ? "Every node within the goal in this run."
                            : ("Outside the goal in this run: " + (outside.empty() ? std::string("none") : list(outside)) +
                               (failed.empty() ? "" : "; failed: " + list(failed)) + ".")
                                  .c_str());
  return 0;
}
