// The boxes a person draws on a graph's frames in the panel (LabelView), and the truth file they
// are saved as: COCO JSON, one of the formats RegionScore, DigitScore and SampleExport read
// (apex_nodes/truth.hpp, docs/tuning.md, "Ground truth from a labelling tool"). No Qt, no ROS.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "apex/core/result.hpp"

namespace apex_rviz_plugin {

/** @brief One box drawn on a frame, in the pixels of the image shown (what RegionScore compares
 *  regions against), and its class. */
struct LabelBox {
  int x = 0, y = 0, width = 0, height = 0;
  std::string label;
};

/** @brief A frame labelled: its stamp, its image's size and its boxes. A frame without boxes is
 *  a frame with nothing to find (a region found there is a false one). */
struct LabelledFrame {
  std::uint64_t stamp = 0;  ///< the image's header stamp, ns
  int width = 0, height = 0;
  std::vector<LabelBox> boxes;
};

/** @brief The frames labelled, by stamp. A frame is labelled from its first box on, or when marked
 *  so (a frame with nothing on it); unmarking leaves it out of the file, boxes and all. */
class FrameLabels {
 public:
  /** @brief Counts the frame at `stamp` (its image `width` × `height`) as labelled. Refused for
   *  stamp 0 (a frame without a stamp matches no regions) or an empty image. */
  apex::Status mark(std::uint64_t stamp, int width, int height);
  /** @brief Leaves the frame at `stamp` out, with its boxes. */
  void unmark(std::uint64_t stamp) { frames_.erase(stamp); }
  /** @brief Adds `box` to the frame at `stamp` (marking it), cut to the image. Refused, naming
   *  its size, for a box without width or height inside the image; and as mark() is. */
  apex::Status add(std::uint64_t stamp, int width, int height, LabelBox box);
  /** @brief Removes box `index` of the frame at `stamp` (the frame stays labelled); false if
   *  there is no such box. */
  bool remove(std::uint64_t stamp, std::size_t index);
  /** @brief Gives box `index` of the frame at `stamp` the class `label`; false if there is no
   *  such box. */
  bool relabel(std::uint64_t stamp, std::size_t index, const std::string& label);
  /** @brief The frame at `stamp`, or nullptr if it is not labelled. */
  const LabelledFrame* frame(std::uint64_t stamp) const;
  const std::map<std::uint64_t, LabelledFrame>& frames() const { return frames_; }
  std::size_t boxCount() const;
  /** @brief The classes of the boxes, each once, in name order. */
  std::vector<std::string> labels() const;

 private:
  std::map<std::uint64_t, LabelledFrame> frames_;
};

/** @brief The name of the frame's image in the truth file: `frame_<sec>.<nsec>.png`, the stamp as
 *  ROS prints it, which the truth readers take back as the frame's stamp. */
std::string frameImageName(std::uint64_t stamp);

/** @brief The frames as a COCO file: one image per frame (in stamp order, named by
 *  frameImageName, with its size), one annotation per box (bbox [x, y, width, height]), one
 *  category per class (ids in name order). */
std::string cocoJson(const FrameLabels& labels);

/** @brief Writes cocoJson(labels) to `path` atomically (the old file or the whole new one).
 *  Refused, naming the path, with no frame labelled, for a name not ending in .json (loadTruth
 *  tells a COCO file by it), or a file that cannot be written (writeFileAtomically's reason). */
apex::Status saveCoco(const FrameLabels& labels, const std::string& path);

}  // namespace apex_rviz_plugin
