// The image library's nodes, each alone, against the OpenCV call it makes, written by hand in a
// plain loop with the same parameters and a reused output: what a node adds to its call (input
// checks, parameter reads, its output buffer, taking and delivering messages). On real 640x480
// images from opencv-doc, OpenCV at one thread for both. This file: the inputs, the table, and
// the image filters' and colour nodes' cases; image_bench_*.cpp the other categories'.
//   apex_bench_images [--quick]   (with the devel space sourced: node types come from pluginlib)
#include <opencv2/core/utility.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/background_segm.hpp>

#include "apex_nodes/features.hpp"
#include "apex_nodes/shapes.hpp"
#include "image_cases.hpp"

namespace apex_bench {
namespace {

constexpr double kAngle = 15 * M_PI / 180;  // Rotate's any-angle case (warpAffine), as in the pipeline bench

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

Inputs inputs(const cv::Mat& bgr_mat, const cv::Mat& round_mat) {
  cv::Mat gray_mat, edges_mat, binary_mat, circles_mat;
  cv::cvtColor(bgr_mat, gray_mat, cv::COLOR_BGR2GRAY);
  cv::Canny(gray_mat, edges_mat, 50, 150);
  cv::threshold(gray_mat, binary_mat, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
  cv::cvtColor(round_mat, circles_mat, cv::COLOR_BGR2GRAY);
  cv::medianBlur(circles_mat, circles_mat, 5);  // as HoughCircles wants it
  Inputs in{image(bgr_mat, "bgr8"),
            image(gray_mat, "mono8"),
            image(edges_mat, "mono8"),
            image(binary_mat, "mono8"),
            image(mosaic(bgr_mat), "bayer_rggb8"),
            image(circles_mat, "mono8"),
            {}};
  // A fixed camera: the background still, a patch of it moving across (8 frames, cycled).
  for (int i = 0; i < 8; ++i) {
    cv::Mat m = bgr_mat.clone();
    bgr_mat(cv::Rect(0, 0, 100, 100)).copyTo(m(cv::Rect(40 + 70 * i, 190, 100, 100)));
    in.moving.push_back(image(m, "bgr8"));
  }
  return in;
}

}  // namespace

std::vector<NodeCase> filterCases(const Inputs& in) {
  const ImagePtr &bgr = in.bgr, &gray = in.gray, &edges = in.edges, &binary = in.binary, &bayer = in.bayer, &circles = in.circles;
  const cv::Matx33d warp(1.0, 0.08, -20.0, 0.03, 1.0, -10.0, 0.0001, 0.0002, 1.0);
  const std::string warp_text = "[1.0, 0.08, -20.0, 0.03, 1.0, -10.0, 0.0001, 0.0002, 1.0]";
  const cv::Mat rotation = cv::getRotationMatrix2D(cv::Point2f(320, 240), kAngle * 180.0 / M_PI, 1.0);
  const cv::Mat kernel3 = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
  const std::string sink = sinkType<Image>();
  auto filter = [&](const char* name, const ImagePtr& frame, const char* input, Params p, const char* text,
                    std::function<void(const cv::Mat&, cv::Mat&)> f, const char* label = nullptr,
                    const char* out_port = "image") {
    return imageCase(label ? label : name, std::string("apex_nodes/") + name, input, {frame}, std::move(p), out_port, sink, text,
                     [f = std::move(f), out = cv::Mat()](const cv::Mat& m) mutable { f(m, out); });
  };
  std::vector<NodeCase> c;
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

  c.push_back(imageCase(
      "FindContours", "apex_nodes/FindContours", "Canny edges", {edges}, {{"mode", "list"}, {"method", "simple"}}, "contours",
      sinkType<apex_nodes::Contours>(), "findContours list, simple",
      [contours = std::vector<std::vector<cv::Point>>(), hierarchy = std::vector<cv::Vec4i>()](const cv::Mat& in) mutable {
        cv::findContours(in, contours, hierarchy, cv::RETR_LIST, cv::CHAIN_APPROX_SIMPLE);
      }));
  c.push_back(imageCase("HoughLines", "apex_nodes/HoughLines", "Canny edges", {edges},
                        {{"rho", "1"}, {"theta", "1"}, {"threshold", "50"}, {"min_line_length", "50"}, {"max_line_gap", "10"}},
                        "lines", sinkType<apex_nodes::Lines>(), "HoughLinesP 1, 1°, 50, 50, 10",
                        [lines = std::vector<cv::Vec4i>()](const cv::Mat& in) mutable {
                          cv::HoughLinesP(in, lines, 1, 1 * CV_PI / 180, 50, 50, 10);
                        }));
  c.push_back(imageCase("HoughCircles", "apex_nodes/HoughCircles", "smarties, gray, median 5", {circles},
                        {{"method", "gradient"},
                         {"dp", "1"},
                         {"min_dist", "20"},
                         {"param1", "100"},
                         {"param2", "30"},
                         {"min_radius", "0"},
                         {"max_radius", "0"}},
                        "circles", sinkType<apex_nodes::Circles>(), "HoughCircles gradient 1, 20, 100, 30",
                        [found = std::vector<cv::Vec3f>()](const cv::Mat& in) mutable {
                          cv::HoughCircles(in, found, cv::HOUGH_GRADIENT, 1, 20, 100, 30, 0, 0);
                        }));
  c.push_back(imageCase("Keypoints (orb)", "apex_nodes/Keypoints", "mono8", {gray},
                        {{"method", "orb"}, {"max_features", "500"}, {"threshold", "0"}}, "keypoints",
                        sinkType<apex_nodes::Keypoints>(), "ORB 500: detectAndCompute",
                        [orb = cv::ORB::create(500, 1.2f, 8, 31, 0, 2, cv::ORB::HARRIS_SCORE, 31, 20),
                         keypoints = std::vector<cv::KeyPoint>(), descriptors = cv::Mat()](const cv::Mat& in) mutable {
                          orb->detectAndCompute(in, cv::noArray(), keypoints, descriptors);
                        }));
  c.push_back(imageCase(
      "BackgroundSubtraction (mog2)", "apex_nodes/BackgroundSubtraction", "8 bgr8 frames, a patch moving", in.moving,
      {{"method", "mog2"}, {"history", "500"}, {"var_threshold", "16"}, {"detect_shadows", "true"}, {"learning_rate", "-1"}},
      "mask", sink, "MOG2 500, 16, shadows: apply",
      [mog = cv::createBackgroundSubtractorMOG2(500, 16, true), mask = cv::Mat()](const cv::Mat& in) mutable {
        mog->apply(in, mask, -1);
      }));
  return c;
}

}  // namespace apex_bench

int main(int argc, char** argv) {
  using namespace apex_bench;
  const bool quick = argc > 1 && std::string(argv[1]) == "--quick";
  const Budget b = Budget::of(quick);
  cv::setNumThreads(1);

  std::printf("## Image nodes against their OpenCV call, 640x480\n\n");
  const cv::Mat building = cv::imread(kData + "/building.jpg"), smarties = cv::imread(kData + "/smarties.png");
  if (building.empty() || smarties.empty()) {
    std::printf("Not measured: %s/building.jpg or smarties.png cannot be read (opencv-doc, scripts/install_deps).\n",
                kData.c_str());
    return 0;
  }
  const Inputs in = inputs(vga(building), vga(smarties));
  std::vector<NodeCase> all;
  for (auto* part : {filterCases, shapeCases, featureCases, cameraCases, segmentationCases, trackingCases, videoCases, dnnCases,
                     ximgprocCases})
    for (auto& c : part(in)) all.push_back(std::move(c));

  std::printf("Each node type alone (a source → the node → a sink, one thread group, loaded through pluginlib)\n");
  std::printf("against the OpenCV call it makes, written by hand in a plain loop with the same parameters and\n");
  std::printf("its output Mat (or vectors, model) reused from frame to frame. The node's time is its firing as\n");
  std::printf("the runtime clocks it (`NodeStats::last_ns`, one TSC read per firing): taking its input, process()\n");
  std::printf("(checks, parameter reads, its output buffer, the call) and delivering its output; not the source's\n");
  std::printf("hop, nor waking the thread. One frame in flight, frames back to back, so each node's output\n");
  std::printf("buffer is free again and reused. The call's time: steady_clock around each call. Input: the middle\n");
  std::printf("640x480 of opencv-doc's building.jpg (bgr8; mono8 by BGR2GRAY; binary by Otsu; edges by Canny\n");
  std::printf("50, 150; a bayer_rggb8 mosaic sampled from it), smarties.png scaled to 640x480 for HoughCircles;\n");
  std::printf("what a node of several inputs gets besides (contours, keypoints, markers drawn in...) is made of\n");
  std::printf("these and said in its row. OpenCV at one thread (cv::setNumThreads(1)) for both. Interleaved in\n");
  std::printf("%d rounds (node, call, node, call, ...), each of N frames per side (N from the call's time, %d to\n", b.rounds,
              b.min_frames);
  std::printf("%d); a round's figure is the median of its frames; median (min–max) over the rounds, µs; the ratio\n",
              b.max_frames);
  std::printf("is per round. Goal: node ≤ call × 1.05 + 20 µs (medians). A type without a bare call to hold it\n");
  std::printf("against says why instead.\n\n");
  measureTable(all, b);
  return 0;
}
