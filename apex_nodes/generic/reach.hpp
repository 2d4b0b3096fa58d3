// How a node is reached from threads of others (a copy's tap, a transport's reply): a function
// runs on its thread group through Node::runLater while the node is there, and is dropped once it
// is gone. Shared by the node and the callbacks it hands out; the node sets itself in setup() and
// clears itself first in its destructor.
#pragma once

#include <functional>
#include <mutex>

#include "apex/core/node.hpp"

namespace apex_nodes {
namespace tuning {

class Reach {
 public:
  void set(apex::Node* node) {
    std::lock_guard<std::mutex> lock(mutex_);
    node_ = node;
  }
  /** Runs `fn` soon on the node's thread group if it is still there; whether it was. */
  bool later(std::function<void()> fn) {
    std::lock_guard<std::mutex> lock(mutex_);  // held: the node's destructor waits for this call
    if (!node_) return false;
    node_->runLater(std::move(fn));
    return true;
  }

 private:
  std::mutex mutex_;
  apex::Node* node_ = nullptr;
};

}  // namespace tuning
}  // namespace apex_nodes
