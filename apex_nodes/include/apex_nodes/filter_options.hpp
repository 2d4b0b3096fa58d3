// What image filters share beyond the ImageFilter shape: depths by OpenCV's names ("16S", "32F")
// and the encoding of a result of another depth, border modes by name, and an image in words for
// errors that name two of them.
#pragma once

#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "apex/core/declare.hpp"
#include "apex_nodes/types.hpp"

namespace apex_nodes {

/** @brief A pixel depth as OpenCV names it: "8U", "16S", "32F"... */
inline std::string depthName(int depth) {
  static const char* const kNames[] = {"8U", "8S", "16U", "16S", "32S", "32F", "64F", "16F"};
  return depth >= 0 && depth < 8 ? kNames[depth] : "depth " + std::to_string(depth);
}

/** @brief The sensor_msgs encoding of a result with `channels` channels of `depth` made from `in`:
 *  the input's when both agree with it; 8 or 16 bits of the input's colour order ("bgr8" gives
 *  "bgr16", "mono16" gives "mono8", one channel gives "mono8" or "mono16"); else the generic
 *  name ("16SC1", "32FC3"). */
inline std::string encodingOf(const Image& in, int channels, int depth) {
  if (channels == in.mat.channels() && depth == in.mat.depth()) return in.encoding;
  if (depth == CV_8U || depth == CV_16U) {
    const std::string bits = depth == CV_8U ? "8" : "16";
    if (channels == 1) return "mono" + bits;
    for (const std::string family : {"bgra", "rgba", "bgr", "rgb"})
      if (channels == in.mat.channels() && (in.encoding == family + "8" || in.encoding == family + "16")) return family + bits;
  }
  return depthName(depth) + "C" + std::to_string(channels);
}

/** @brief An image in words for an error: "640x480 'bgr8' (8UC3)". */
inline std::string imageWords(const Image& image) {
  return std::to_string(image.mat.cols) + "x" + std::to_string(image.mat.rows) + " '" + image.encoding + "' (" +
         depthName(image.mat.depth()) + "C" + std::to_string(image.mat.channels()) + ")";
}

/** @brief How filters make up pixels beyond the image's edge, by name; the first is OpenCV's
 *  default (BORDER_REFLECT_101: gfedcb|abcdefgh|gfedcba). A choice of them:
 *  apex::param::choice<int>("border_type", borderModes()). */
inline const std::vector<apex::Option<int>>& borderModes() {
  static const std::vector<apex::Option<int>> modes{{"reflect_101", cv::BORDER_REFLECT_101},
                                                    {"replicate", cv::BORDER_REPLICATE},
                                                    {"reflect", cv::BORDER_REFLECT},
                                                    {"constant", cv::BORDER_CONSTANT}};
  return modes;
}

}  // namespace apex_nodes
