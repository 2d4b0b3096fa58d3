// Reuses a node's previous output when nobody else holds it any more: messages
// stay immutable (a shared one is never written), and a steady pipeline
// allocates no new pixels or points per frame (no allocation, zero-fill or page
// faults: a new megabyte costs ~0.1 ms in faults alone).
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

#include "apex_nodes/types.hpp"

namespace apex_nodes {

/** @brief A node's last results (an image, a cloud's points, its x, y, z view), each handed out
 *  again once nobody else holds it, the most recent first (its memory is the warmest in cache).
 *  Up to kKept are kept: in a pipeline of thread groups the frame before is still in use
 *  downstream while the node makes the next, and with one kept every frame was allocated anew
 *  (the demo cut in two groups: its Rotate's 900 kB per frame). */
template <class T>
class Reused {
 public:
  static constexpr std::size_t kKept = 3;
  /** @brief A previous object nobody else holds (stale: the caller sets every member), else a new one. */
  std::shared_ptr<T> next() {
    for (std::size_t i = 0; i < kept_.size(); ++i)
      if (kept_[i].use_count() == 1) {
        std::rotate(kept_.begin(), kept_.begin() + long(i), kept_.begin() + long(i) + 1);  // to the front
        return kept_.front();
      }
    if (kept_.size() == kKept) kept_.pop_back();  // all still held downstream: the oldest is let go
    kept_.insert(kept_.begin(), std::make_shared<T>());
    return kept_.front();
  }

 private:
  std::vector<std::shared_ptr<T>> kept_;  // the most recently handed out first
};

class OutputBuffer {
 public:
  /** @brief An image to fill, with `in`'s header: the previous output if it is unshared. */
  std::shared_ptr<Image> next(const Image& in) {
    std::shared_ptr<Image> out = images_.next();
    out->header = in.header;
    out->owner.reset();
    return out;
  }

 private:
  Reused<Image> images_;
};

}  // namespace apex_nodes
