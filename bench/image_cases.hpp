// What apex_bench_images' case files share: the input images (made once from opencv-doc's) and
// the ways to make a case of them. Each image_bench_*.cpp adds the cases of some categories.
#pragma once

#include <sensor_msgs/CameraInfo.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "apex_nodes/types.hpp"
#include "node_vs_call.hpp"

namespace apex_bench {

using apex_nodes::Image;
using ImagePtr = std::shared_ptr<const Image>;

const std::string kData = "/usr/share/doc/opencv-doc/examples/data";  // scripts/install_deps installs opencv-doc

/** The bench's input images, 640x480, made once (image_bench.cpp says how). */
struct Inputs {
  ImagePtr bgr, gray, edges, binary, bayer, circles;
  std::vector<ImagePtr> moving;  ///< 8 bgr8 frames of a fixed camera, a patch moving across
};

inline ImagePtr image(cv::Mat mat, const std::string& encoding) {
  auto i = std::make_shared<Image>();
  i->header.frame_id = "camera";
  i->header.seq = 1;
  i->encoding = encoding;
  i->mat = std::move(mat);
  return i;
}

template <class T>
apex::Message msg(std::shared_ptr<T> payload) {
  return apex::Message::share<std::remove_const_t<T>>(std::move(payload));
}

/** A number as YAML text that reads back as the same double. */
inline std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

/** A node of one image input ("image") and one output, fed `frames` in turn, against `call` on
 *  the same frame's pixels. */
inline NodeCase imageCase(std::string label, std::string type, std::string input, std::vector<ImagePtr> frames, Params params,
                          std::string out_port, std::string sink, std::string call_text,
                          std::function<void(const cv::Mat&)> call) {
  NodeCase c;
  c.label = std::move(label);
  c.type = std::move(type);
  c.input = std::move(input);
  c.feed = feedType<Image>();
  c.in_ports = {"image"};
  for (const auto& f : frames) c.frames.push_back({msg(f)});
  c.params = std::move(params);
  c.out_port = std::move(out_port);
  c.sink = std::move(sink);
  c.call_text = std::move(call_text);
  c.call = [frames = std::move(frames), call = std::move(call)](std::size_t i) { call(frames[i]->mat); };
  return c;
}

// The case files: each gives its categories' cases on the inputs.
/** left_intrinsics.yml's model as a ROS message (R identity, P = [K | 0]); nullptr if unreadable
 *  (image_bench_cameras.cpp). */
std::shared_ptr<const sensor_msgs::CameraInfo> leftCamera();

std::vector<NodeCase> filterCases(const Inputs& in);  // image_bench.cpp: image filters, colour, the first detectors
std::vector<NodeCase> shapeCases(const Inputs& in);  // image_bench_shapes.cpp: two-input filters, channels, contours, drawing
std::vector<NodeCase> featureCases(const Inputs& in);  // image_bench_features.cpp: features, motion, detection
std::vector<NodeCase> cameraCases(const Inputs& in);  // image_bench_cameras.cpp: cameras and stereo, learning
std::vector<NodeCase> segmentationCases(
    const Inputs& in);  // image_bench_segmentation.cpp: watershed, GrabCut, k-means, superpixels
std::vector<NodeCase> trackingCases(const Inputs& in);  // image_bench_tracking.cpp: Tracker, KalmanFilter, MultiObjectTracker
std::vector<NodeCase> videoCases(
    const Inputs& in);  // image_bench_video.cpp: VideoWriter, ImageSequenceWriter, SolvePnP, Stitcher
std::vector<NodeCase> dnnCases(const Inputs& in);  // image_bench_dnn.cpp: DnnNetwork, on a network written as ONNX
std::vector<NodeCase> ximgprocCases(const Inputs& in);  // image_bench_ximgproc.cpp: ximgproc's filters, thinning, lines

}  // namespace apex_bench
