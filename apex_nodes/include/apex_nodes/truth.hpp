// The ground truth that apex_make_demo_bag writes next to its bag (per frame, by stamp, the signs'
// boxes in the upright scene and the digit on each, and how the camera saw the scene), or that a
// labelling tool wrote for images named by their frames' stamps (boxes in the image).
// Shared by the nodes that score or label regions (RegionScore, DigitScore, SampleExport).
#pragma once

#include <cstdint>
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "apex_nodes/types.hpp"

namespace apex_nodes {

/** @brief One sign: its box in the upright scene and its digit (-1 if the file has none). */
struct TruthSign {
  cv::Rect box;
  int digit = -1;
};

struct Truth {
  std::map<std::uint64_t, std::vector<TruthSign>> frames;  ///< by stamp, nanoseconds
  cv::Size scene;  ///< empty: boxes are in the image's frame
  int rotation = 0;  ///< degrees clockwise: the image is the scene turned
  bool has_digits = false;  ///< every frame lists its signs' digits

  /** @brief Throws std::invalid_argument naming `path` unless every sign has its digit. */
  void requireDigits(const std::string& path) const;
  /** @brief The frame within a millisecond of `ns`, or nullptr. */
  const std::vector<TruthSign>* frameAt(std::uint64_t ns) const;
  /** @brief The frame of `regions` with its boxes in the regions' image; throws
   *  std::invalid_argument naming the stamp if there is none. */
  std::vector<TruthSign> signsFor(const Regions& regions, const std::string& path) const;
};

/** @brief Reads the ground truth at `path`, by its kind: apex_make_demo_bag's YAML (.yaml, .yml or
 *  any other name), a COCO or labelme .json (by its keys), a Pascal VOC .xml, a YOLO .txt, or a
 *  folder of one tool's per-image files (.xml, .json or .txt). A labelling tool's image is the
 *  frame whose stamp its name holds (frame_<sec>.<nsec>.png, <nanoseconds>.png); its boxes are in
 *  the image's frame; a label "0".."9" is the sign's digit, and has_digits says every label is one.
 *  Throws std::invalid_argument naming the file, and the line or entry, and the problem. */
Truth loadTruth(const std::string& path);

/** @brief A truth box in the frame of an image of `size` (the scene, or the scene turned by the
 *  camera's 90 or 270 degrees); throws std::invalid_argument if the sizes do not fit. */
cv::Rect toImage(const Truth& t, const cv::Rect& box, const cv::Size& size);

/** @brief Matches truth signs to regions one-to-one, best overlap (intersection over union)
 *  first, each pair overlapping at least `iou`: (sign index, region index) pairs. */
std::vector<std::pair<int, int>> matchSigns(const std::vector<TruthSign>& signs, const std::vector<Region>& regions, double iou);

/** @brief Loads a truth file when first needed, again after its path changes. */
class TruthFile {
 public:
  void reset() { loaded_.reset(); }
  /** @brief The truth at `path`; throws std::invalid_argument for an empty path or a bad file. */
  const Truth& get(const std::string& path);

 private:
  std::unique_ptr<Truth> loaded_;
};

}  // namespace apex_nodes
