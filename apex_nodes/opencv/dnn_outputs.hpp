// What DnnNetwork makes of a network's output besides a class: SSD-style detection rows made boxes
// of the image, and per-pixel class scores made a mask of class indices. Free functions of the
// output alone, so that the node's file keeps to running the network.
#pragma once

#include <algorithm>
#include <map>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "apex_nodes/types.hpp"

namespace apex_nodes {

/** @brief A blob's shape as text, e.g. "[1, 1, 100, 7]". */
inline std::string shapeOf(const cv::Mat& blob) {
  std::string text = "[";
  for (int i = 0; i < blob.dims; ++i) text += (i == 0 ? "" : ", ") + std::to_string(blob.size[i]);
  return text + "]";
}

/** @brief The detections in `rows`, a float output in the layout of SSD's DetectionOutput layer
 *  ([1, 1, N, 7]: image_id, class_id, confidence, x1, y1, x2, y2, the corners relative to the
 *  network's input, 0..1), as regions of an image of `size`: the corners scaled to it and rounded,
 *  the box cut to the image (a box with nothing left in it is dropped), label the class id; only
 *  rows whose confidence is above `min_confidence`. Then, class by class, cv::dnn::NMSBoxes drops
 *  each box that overlaps a more confident one of its class by more than `nms_threshold`
 *  (intersection over union). Largest confidence first; equal ones by class id, then in the
 *  rows' order. The image_id is not read (one image per run). Throws std::invalid_argument
 *  naming the shape if `rows` is not [1, 1, N, 7]. */
inline std::vector<Region> detectionsOf(const cv::Mat& rows, const cv::Size& size, float min_confidence, float nms_threshold) {
  if (rows.dims != 4 || rows.size[0] != 1 || rows.size[1] != 1 || rows.size[3] != 7 || rows.depth() != CV_32F)
    throw std::invalid_argument("the network's output is " + shapeOf(rows) +
                                ": task 'detect' needs [1, 1, N, 7], the rows of SSD's DetectionOutput (image_id, "
                                "class_id, confidence, x1, y1, x2, y2, the corners relative to the input, 0..1)");
  const cv::Rect frame(cv::Point(0, 0), size);
  std::map<int, std::vector<Region>> by_class;  // ordered: classes in ascending order
  for (int i = 0; i < rows.size[2]; ++i) {
    const float* d = rows.ptr<float>() + 7 * i;
    if (!(d[2] > min_confidence)) continue;
    Region r;
    r.box = cv::Rect(cv::Point(cvRound(d[3] * size.width), cvRound(d[4] * size.height)),
                     cv::Point(cvRound(d[5] * size.width), cvRound(d[6] * size.height))) &
            frame;
    if (r.box.empty()) continue;
    r.area = r.box.area();
    r.centroid = cv::Point2d(r.box.x + r.box.width / 2.0, r.box.y + r.box.height / 2.0);
    r.label = cvRound(d[1]);
    r.confidence = d[2];
    by_class[r.label].push_back(r);
  }
  std::vector<Region> kept;
  for (const auto& [label, candidates] : by_class) {
    std::vector<cv::Rect> boxes;
    std::vector<float> scores;
    for (const Region& r : candidates) boxes.push_back(r.box), scores.push_back(static_cast<float>(r.confidence));
    std::vector<int> keep;
    cv::dnn::NMSBoxes(boxes, scores, min_confidence, nms_threshold, keep);
    for (int k : keep) kept.push_back(candidates[k]);
  }
  std::stable_sort(kept.begin(), kept.end(), [](const Region& a, const Region& b) { return a.confidence > b.confidence; });
  return kept;
}

/** @brief The class of each pixel of `scores`, a float output [1, C, H, W] of 2 to 65536 classes:
 *  the index of its largest score (the first of equal ones), CV_8U for up to 256 classes, else
 *  CV_16U; resized to `size` by nearest neighbour (cv::INTER_NEAREST). Throws
 *  std::invalid_argument naming the shape for another. */
inline cv::Mat classMask(const cv::Mat& scores, const cv::Size& size) {
  if (scores.dims != 4 || scores.size[0] != 1 || scores.size[1] < 2 || scores.size[1] > 65536 || scores.size[2] < 1 ||
      scores.size[3] < 1 || scores.depth() != CV_32F)
    throw std::invalid_argument("the network's output is " + shapeOf(scores) +
                                ": task 'segment' needs [1, C, H, W], a score per class and pixel for 2 to 65536 classes");
  const int classes = scores.size[1], rows = scores.size[2], cols = scores.size[3];
  const auto plane = [&](int c) { return cv::Mat(rows, cols, CV_32F, const_cast<float*>(scores.ptr<float>(0, c))); };
  cv::Mat index(rows, cols, classes <= 256 ? CV_8U : CV_16U, cv::Scalar(0));
  cv::Mat best = plane(0).clone(), higher;
  for (int c = 1; c < classes; ++c) {
    cv::compare(plane(c), best, higher, cv::CMP_GT);  // strictly: the first maximum wins
    plane(c).copyTo(best, higher);
    index.setTo(c, higher);
  }
  cv::Mat mask;
  cv::resize(index, mask, size, 0, 0, cv::INTER_NEAREST);
  return mask;
}

}  // namespace apex_nodes
