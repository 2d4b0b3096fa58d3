// What the feature and motion nodes exchange: keypoints with their descriptors, matches between
// two sets of them, the homography the matches give, points tracked from one frame to the next.
// Like Regions (types.hpp), each keeps the header of the frame it came from; a node never
// changes one, it sends a new one. Also the two conversions those nodes make of their images.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "apex_nodes/image_check.hpp"
#include "apex_nodes/types.hpp"

namespace apex_nodes {

/** @brief Keypoints found in one image (Keypoints node), with that image's header and size. */
struct Keypoints {
  std_msgs::Header header;
  cv::Size image_size;
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;  ///< row i describes keypoints[i]; empty when the method has none (fast, gftt)
  std::string method;  ///< the detector: "orb", "akaze", "brisk", "sift", "fast" or "gftt"
  int norm_type = cv::NORM_L2;  ///< the norm to match the descriptors with: cv::NORM_HAMMING for binary ones
};

/** @brief Matches of one image's keypoints (query) to another's (train), e.g. from MatchDescriptors.
 *  match.queryIdx indexes query->keypoints, match.trainIdx train->keypoints. The header is the
 *  query's. */
struct Matches {
  std_msgs::Header header;
  std::vector<cv::DMatch> matches;
  std::shared_ptr<const Keypoints> query, train;
};

/** @brief The homography from the query image to the train image of some Matches (FindHomography),
 *  with their header. `matrix` is empty when none was found, or when it had too few inliers (then
 *  `inliers` and `inlier_mask` still say what it had). */
struct Homography {
  std_msgs::Header header;
  cv::Size image_size;  ///< the query image's: its corners mapped by `matrix` outline it in the train image
  cv::Mat matrix;  ///< 3x3 CV_64F, query pixel -> train pixel; or empty
  std::vector<uchar> inlier_mask;  ///< one per match: 1 for an inlier
  int inliers = 0;
};

/** @brief Points tracked from the previous frame to this one (OpticalFlowLK), with this frame's
 *  header and size: previous[i] moved to current[i] if status[i] is 1 (else it was lost). */
struct Tracks {
  std_msgs::Header header;
  cv::Size image_size;
  std::vector<cv::Point2f> previous, current;
  std::vector<uchar> status;
};

/** @brief The header as the next message in a chain should carry it. */
inline const std_msgs::Header& headerOf(const Keypoints& k) { return k.header; }
inline const std_msgs::Header& headerOf(const Matches& m) { return m.header; }
inline const std_msgs::Header& headerOf(const Homography& h) { return h.header; }
inline const std_msgs::Header& headerOf(const Tracks& t) { return t.header; }

/** @brief An 8-bit image (1, 3 or 4 channels) as the single-channel gray image detectors and
 *  optical flow work on: the pixels themselves if it is gray already (to read only), else
 *  converted into `scratch` (cv::cvtColor's BGR2GRAY, or RGB2GRAY for "rgb8"/"rgba8"), the
 *  node's own image reused from frame to frame, and returned. Errors name what it got. */
inline cv::Mat gray8(const Image& in, cv::Mat& scratch) {
  requireImage(in, "134");
  if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image ('" + in.encoding + "')");
  if (in.mat.channels() == 1) return in.mat;
  const bool rgb = in.encoding.rfind("rgb", 0) == 0;
  if (in.mat.channels() == 3) cv::cvtColor(in.mat, scratch, rgb ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY);
  else cv::cvtColor(in.mat, scratch, rgb ? cv::COLOR_RGBA2GRAY : cv::COLOR_BGRA2GRAY);
  return scratch;
}

/** @brief An 8-bit image (1, 3 or 4 channels) as bgr8 in `out`, to draw on: never `in`'s pixels. */
inline void bgr8(const Image& in, cv::Mat& out) {
  requireImage(in, "134");
  if (in.mat.depth() != CV_8U) throw std::invalid_argument("needs an 8-bit image ('" + in.encoding + "')");
  const bool rgb = in.encoding.rfind("rgb", 0) == 0;
  if (in.mat.channels() == 1) cv::cvtColor(in.mat, out, cv::COLOR_GRAY2BGR);
  else if (in.mat.channels() == 4) cv::cvtColor(in.mat, out, rgb ? cv::COLOR_RGBA2BGR : cv::COLOR_BGRA2BGR);
  else if (rgb) cv::cvtColor(in.mat, out, cv::COLOR_RGB2BGR);
  else in.mat.copyTo(out);
}

}  // namespace apex_nodes

APEX_TYPE_NAME(apex_nodes::Keypoints, "apex_nodes/Keypoints");
APEX_TYPE_NAME(apex_nodes::Matches, "apex_nodes/Matches");
APEX_TYPE_NAME(apex_nodes::Homography, "apex_nodes/Homography");
APEX_TYPE_NAME(apex_nodes::Tracks, "apex_nodes/Tracks");
