// RegionScore: how well a frame's regions (BlobDetection's) match the ground truth that
// apex_make_demo_bag writes: frames found by stamp, truth boxes matched one-to-one to regions
// whose overlap (intersection over union) reaches `iou`, best overlaps first.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <map>

#include "apex/core/registry.hpp"
#include "apex_nodes/types.hpp"

namespace apex_nodes {
namespace {

/** The truth file: boxes per frame stamp, in the upright scene, and how the camera saw it. */
struct Truth {
  std::map<std::uint64_t, std::vector<cv::Rect>> frames;  // by stamp, nanoseconds
  cv::Size scene;                                          // empty: boxes are in the image's frame
  int rotation = 0;                                        // degrees clockwise: the image is the scene turned
};

Truth loadTruth(const std::string& path) {
  Truth t;
  try {
    const YAML::Node root = YAML::LoadFile(path);
    for (const auto& f : root["frames"]) {
      auto& boxes = t.frames[f["stamp"].as<std::uint64_t>()];
      for (const auto& b : f["boxes"]) boxes.emplace_back(b[0].as<int>(), b[1].as<int>(), b[2].as<int>(), b[3].as<int>());
    }
    if (root["scene_size"]) t.scene = cv::Size(root["scene_size"][0].as<int>(), root["scene_size"][1].as<int>());
    if (root["camera_rotation"]) t.rotation = ((root["camera_rotation"].as<int>() % 360) + 360) % 360;
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument("cannot read the ground truth '" + path + "': " + e.what());
  }
  if (t.frames.empty()) throw std::invalid_argument("the ground truth '" + path + "' lists no frames");
  return t;
}

/** A truth box in the frame of an image of `size`: as it is when the image is the upright
 *  scene, turned with the camera when the image is the scene turned by 90 or 270 degrees. */
cv::Rect toImage(const Truth& t, const cv::Rect& b, const cv::Size& size) {
  if (t.scene.empty() || size == t.scene) return b;
  const int W = t.scene.width, H = t.scene.height;
  if (size == cv::Size(H, W) && t.rotation == 90) return {H - b.y - b.height, b.x, b.height, b.width};
  if (size == cv::Size(H, W) && t.rotation == 270) return {b.y, W - b.x - b.width, b.height, b.width};
  throw std::invalid_argument("the regions come from a " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                              " image; the ground truth's scene is " + std::to_string(W) + "x" + std::to_string(H) +
                              " seen turned by " + std::to_string(t.rotation) + " degrees");
}

double iou(const cv::Rect& a, const cv::Rect& b) {
  const double inter = (a & b).area();
  const double uni = a.area() + b.area() - inter;
  return uni > 0 ? inter / uni : 0;
}

/** Matches: each truth box to at most one region, best overlaps first. */
int matches(const std::vector<cv::Rect>& truth, const std::vector<Region>& found, double threshold) {
  std::vector<std::tuple<double, int, int>> pairs;  // (iou, truth, region)
  for (std::size_t t = 0; t < truth.size(); ++t)
    for (std::size_t r = 0; r < found.size(); ++r)
      if (const double o = iou(truth[t], found[r].box); o >= threshold) pairs.emplace_back(o, t, r);
  std::sort(pairs.rbegin(), pairs.rend());
  std::vector<bool> truth_used(truth.size()), found_used(found.size());
  int n = 0;
  for (const auto& [o, t, r] : pairs) {
    if (truth_used[t] || found_used[r]) continue;
    truth_used[t] = found_used[r] = true;
    ++n;
  }
  return n;
}

}  // namespace

class RegionScore : public apex::Node {
 public:
  static apex::Manifest manifest() {
    return apex::Manifest("Scores a frame's regions against the ground truth (apex_make_demo_bag's truth file)")
        .input<Regions>("regions", "e.g. BlobDetection's")
        .output<double>("precision", "matched regions / regions (1 if none were found)")
        .output<double>("recall", "matched truth boxes / truth boxes (1 if the frame has none)")
        .output<double>("f1", "2 precision recall / (precision + recall); 0 if both are 0")
        .param(apex::param::path("truth", "", apex::PathMode::Read)
                   .describe("the ground truth: frames by stamp, boxes in the upright scene and the camera's rotation"))
        .param(apex::param::range("iou", 0.05, 1.0, 0.05, 0.5).describe("overlap a region needs to match a truth box"));
  }
  void parameterChanged(const std::string& name) override {
    if (name == "truth") loaded_.reset();  // read on the next frame, where an error shows
  }
  void process() override {
    const Regions& in = *regions_.get();
    const Truth& truth = load();
    const std::vector<cv::Rect>* boxes = frameAt(truth, in.header.stamp.toNSec());
    if (!boxes)
      throw std::invalid_argument("the ground truth '" + truth_.get() + "' has no frame at stamp " +
                                  std::to_string(in.header.stamp.toSec()) + " s");
    std::vector<cv::Rect> seen;
    for (const auto& b : *boxes) seen.push_back(toImage(truth, b, in.image_size));
    const int n = matches(seen, in.regions, iou_.get());
    const double precision = in.regions.empty() ? 1.0 : static_cast<double>(n) / in.regions.size();
    const double recall = seen.empty() ? 1.0 : static_cast<double>(n) / seen.size();
    precision_.publish(precision);
    recall_.publish(recall);
    f1_.publish(precision + recall > 0 ? 2 * precision * recall / (precision + recall) : 0.0);
  }

 private:
  const Truth& load() {
    if (!loaded_) {
      if (truth_.get().empty()) throw std::invalid_argument("no ground truth: set 'truth' to the truth file of the bag");
      loaded_ = std::make_unique<Truth>(loadTruth(truth_.get()));
    }
    return *loaded_;
  }
  /** The truth frame within a millisecond of `ns`, or nullptr. */
  static const std::vector<cv::Rect>* frameAt(const Truth& t, std::uint64_t ns) {
    constexpr std::uint64_t kTolerance = 1000000;
    auto it = t.frames.lower_bound(ns >= kTolerance ? ns - kTolerance : 0);
    return it != t.frames.end() && it->first <= ns + kTolerance ? &it->second : nullptr;
  }

  apex::Input<Regions> regions_{this, "regions"};
  apex::Output<double> precision_{this, "precision"};
  apex::Output<double> recall_{this, "recall"};
  apex::Output<double> f1_{this, "f1"};
  apex::Param<std::string> truth_{this, "truth"};
  apex::Param<double> iou_{this, "iou"};
  std::unique_ptr<Truth> loaded_;
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::RegionScore, "apex_nodes/RegionScore");
