#include "trace_ring.hpp"

#include <algorithm>

namespace apex {
namespace detail {

namespace {
std::size_t powerOfTwoAtLeast(std::size_t n) {
  std::size_t p = 1;
  while (p < n) p <<= 1;
  return p;
}
}  // namespace

TraceRing::TraceRing(std::size_t capacity)
    : slots_(new Slot[powerOfTwoAtLeast(std::max<std::size_t>(capacity, 2))]),
      mask_(powerOfTwoAtLeast(std::max<std::size_t>(capacity, 2)) - 1) {}

std::vector<TraceRecord> TraceRing::read() const {
  const auto relaxed = std::memory_order_relaxed;
  const std::uint64_t before = head_.load(std::memory_order_acquire);
  const std::uint64_t first = before > capacity() ? before - capacity() : 0;
  std::vector<TraceRecord> out;
  out.reserve(before - first);
  for (std::uint64_t i = first; i < before; ++i) {
    const Slot& s = slots_[i & mask_];
    out.push_back({s.node.load(relaxed), s.start.load(relaxed), s.end.load(relaxed), s.frame.load(relaxed)});
  }
  // What the writer reached meanwhile: slots it wrote again since `first`, and the one it may be
  // writing now (head_ not yet moved past it), may have been read half-new.
  std::atomic_thread_fence(std::memory_order_acquire);
  const std::uint64_t after = head_.load(relaxed);
  const std::uint64_t overwritten = after + 1 > capacity() ? after + 1 - capacity() : 0;
  if (overwritten > first) out.erase(out.begin(), out.begin() + std::min<std::uint64_t>(overwritten - first, out.size()));
  return out;
}

}  // namespace detail
}  // namespace apex
