// The ground truth of apex_make_demo_bag: reading it, and matching regions to its signs (the
// other formats' readers: truth_formats.cpp).
#include "apex_nodes/truth.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <stdexcept>
#include <tuple>

#include "truth_formats.hpp"

namespace apex_nodes {

Truth truth_formats::readDemoYaml(const std::string& path) {
  Truth t;
  t.has_digits = true;
  try {
    const YAML::Node root = YAML::LoadFile(path);
    for (const auto& f : root["frames"]) {
      auto& signs = t.frames[f["stamp"].as<std::uint64_t>()];
      for (const auto& b : f["boxes"]) signs.push_back({{b[0].as<int>(), b[1].as<int>(), b[2].as<int>(), b[3].as<int>()}, -1});
      const YAML::Node digits = f["digits"];
      if (!digits || digits.size() != signs.size()) {
        t.has_digits = false;
        continue;
      }
      for (std::size_t i = 0; i < signs.size(); ++i) signs[i].digit = digits[i].as<int>();
    }
    if (root["scene_size"]) t.scene = cv::Size(root["scene_size"][0].as<int>(), root["scene_size"][1].as<int>());
    if (root["camera_rotation"]) t.rotation = ((root["camera_rotation"].as<int>() % 360) + 360) % 360;
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument("cannot read the ground truth '" + path + "': " + e.what());
  }
  if (t.frames.empty()) throw std::invalid_argument("the ground truth '" + path + "' lists no frames");
  return t;
}

void Truth::requireDigits(const std::string& path) const {
  if (!has_digits)
    throw std::invalid_argument("the ground truth '" + path + "' lists no digits for some signs: a labelling tool's labels " +
                                "must all be 0..9 (an older apex_make_demo_bag's file: make the bag again)");
}

const std::vector<TruthSign>* Truth::frameAt(std::uint64_t ns) const {
  constexpr std::uint64_t kTolerance = 1000000;
  auto it = frames.lower_bound(ns >= kTolerance ? ns - kTolerance : 0);
  return it != frames.end() && it->first <= ns + kTolerance ? &it->second : nullptr;
}

std::vector<TruthSign> Truth::signsFor(const Regions& regions, const std::string& path) const {
  const std::vector<TruthSign>* signs = frameAt(regions.header.stamp.toNSec());
  if (!signs)
    throw std::invalid_argument("the ground truth '" + path + "' has no frame at stamp " +
                                std::to_string(regions.header.stamp.toSec()) + " s");
  std::vector<TruthSign> seen = *signs;
  for (auto& s : seen) s.box = toImage(*this, s.box, regions.image_size);
  return seen;
}

cv::Rect toImage(const Truth& t, const cv::Rect& b, const cv::Size& size) {
  if (t.scene.empty() || size == t.scene) return b;
  const int W = t.scene.width, H = t.scene.height;
  if (size == cv::Size(H, W) && t.rotation == 90) return {H - b.y - b.height, b.x, b.height, b.width};
  if (size == cv::Size(H, W) && t.rotation == 270) return {b.y, W - b.x - b.width, b.height, b.width};
  throw std::invalid_argument("the regions come from a " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                              " image; the ground truth's scene is " + std::to_string(W) + "x" + std::to_string(H) +
                              " seen turned by " + std::to_string(t.rotation) + " degrees");
}

namespace {

double overlap(const cv::Rect& a, const cv::Rect& b) {
  const double inter = (a & b).area();
  const double uni = a.area() + b.area() - inter;
  return uni > 0 ? inter / uni : 0;
}

}  // namespace

std::vector<std::pair<int, int>> matchSigns(const std::vector<TruthSign>& signs, const std::vector<Region>& regions, double iou) {
  std::vector<std::tuple<double, int, int>> pairs;  // (overlap, sign, region)
  for (std::size_t s = 0; s < signs.size(); ++s)
    for (std::size_t r = 0; r < regions.size(); ++r)
      if (const double o = overlap(signs[s].box, regions[r].box); o >= iou) pairs.emplace_back(o, s, r);
  std::sort(pairs.rbegin(), pairs.rend());
  std::vector<bool> sign_used(signs.size()), region_used(regions.size());
  std::vector<std::pair<int, int>> out;
  for (const auto& [o, s, r] : pairs) {
    if (sign_used[s] || region_used[r]) continue;
    sign_used[s] = region_used[r] = true;
    out.emplace_back(s, r);
  }
  return out;
}

const Truth& TruthFile::get(const std::string& path) {
  if (!loaded_) {
    if (path.empty()) throw std::invalid_argument("no ground truth: set 'truth' to the truth file of the bag");
    loaded_ = std::make_unique<Truth>(loadTruth(path));
  }
  return *loaded_;
}

}  // namespace apex_nodes
