// What the flow nodes (Buffer, Accumulate, Latch, Statistics, Compare, ...) share: the list of
// messages they send, a number read from an input of any type, a window of the newest values, and
// the rule that a new pass of a sequence starts without the last one's state.
#pragma once

#include <cmath>
#include <deque>
#include <stdexcept>
#include <string>
#include <vector>

#include "apex/core/node.hpp"

namespace apex_nodes {

/** @brief Several messages of any types as one message, oldest first (Buffer, Accumulate). */
using MessageList = std::vector<apex::Message>;

/** @brief A number message (int or double) as a double. Throws std::invalid_argument naming the
 *  input and what it carries for another type, and for NaN. */
inline double numberOf(const apex::Message& m, const std::string& input) {
  double v;
  if (auto d = m.as<double>()) v = *d;
  else if (auto i = m.as<int>()) v = *i;
  else throw std::invalid_argument("input '" + input + "' carries " + m.typeName() + ", not a number (int or double)");
  if (std::isnan(v)) throw std::invalid_argument("input '" + input + "' is NaN, not a number");
  return v;
}

/** @brief Adds `value` to `window` and keeps its newest `size` values (all of them if they fit). */
template <class T>
void pushWithin(std::deque<T>& window, T value, std::size_t size) {
  window.push_back(std::move(value));
  while (window.size() > size) window.pop_front();
}

/** @brief A flow node with state: its `reset` slot forgets it, and so does the end of a sequence
 *  (the token is passed on), so a new pass of a bag does not get the last pass's values (as Delay). */
class StatefulFlowNode : public apex::Node {
 public:
  /** Forgets what the node holds; runs between firings, or at the end of a sequence. */
  virtual void reset() = 0;
  void endOfSequence() override {
    reset();
    endSequence();
  }
};

}  // namespace apex_nodes

APEX_TYPE_NAME(apex_nodes::MessageList, "list<any>");
