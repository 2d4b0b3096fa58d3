// NodeState's inline members that run at every firing, defined out of the class (node_state.hpp
// includes this after it; each is described where the class declares it): inline, as they were
// in the class, since a call would cost the firing path.
#pragma once

#include <atomic>
#include <cstdint>

#include "node_state.hpp"

namespace apex {
namespace detail {

inline void NodeState::nameFrames(std::int64_t taken) {
  frame_ = taken;
  starts_frame_ = false;
  if (frame_ == 0)
    for (auto& out : outputs_)
      if ((frame_ = out.pending.payloadStamp()) != 0) {
        starts_frame_ = true;
        break;
      }
  for (auto& out : outputs_) out.pending.setFrame(frame_);
}

inline void NodeState::recordFiring(bool timed, std::int64_t t, std::int64_t end) {
  const auto relaxed = std::memory_order_relaxed;  // one writer: no locked instructions
  last_fired_.store(end, relaxed);
  if (last_had_data_) last_sent_.store(end - t, relaxed);  // its start (untimed: a read before it)
  if (timed || !last_had_data_ || frame_ > 0) return recordTimedOrNothing(timed, t);
  --untimed_left_;
  firings_.store(firings_.load(relaxed) + 1, relaxed);
}

}  // namespace detail
}  // namespace apex
