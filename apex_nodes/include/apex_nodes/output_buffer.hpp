// Reuses a node's previous output image when nobody else holds it any more:
// messages stay immutable (a shared one is never written), and a steady
// pipeline allocates no new pixels per frame.
#pragma once

#include <memory>

#include "apex_nodes/types.hpp"

namespace apex_nodes {

class OutputBuffer {
 public:
  /** @brief An image to fill, with `in`'s header: the previous output if it is unshared. */
  std::shared_ptr<Image> next(const Image& in) {
    if (!last_ || last_.use_count() > 1) last_ = std::make_shared<Image>();
    last_->header = in.header;
    last_->owner.reset();
    return last_;
  }

 private:
  std::shared_ptr<Image> last_;
};

}  // namespace apex_nodes
