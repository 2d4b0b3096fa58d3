// A thread group's frame trace: the last firings, in a ring its own thread writes without a lock
// and anyone may read. Off by default; on, a firing costs two clock reads and four relaxed stores
// (docs/benchmarks.md, "The frame trace's cost per hop").
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

namespace apex {
namespace detail {

/** One firing as the ring keeps it (ticks: ticks.hpp). */
struct TraceRecord {
  static constexpr std::uint64_t kStartsFrame = 1ull << 63;  // in `node`: the firing began its frame
  std::uint64_t node = 0;  // NodeState::seq, | kStartsFrame
  std::int64_t start = 0, end = 0;
  std::int64_t frame = 0;  // Message::frame
};

class TraceRing {
 public:
  /** Room for `capacity` firings (rounded up to a power of two); the oldest go first. */
  explicit TraceRing(std::size_t capacity);
  /** The group's own thread only. */
  void write(const TraceRecord& r) {
    const auto relaxed = std::memory_order_relaxed;
    const std::uint64_t h = head_.load(relaxed);
    Slot& s = slots_[h & mask_];
    // (a reader that sees one of the stores below then also sees head_ at h: read() drops the slot)
    std::atomic_thread_fence(std::memory_order_release);
    s.node.store(r.node, relaxed);
    s.start.store(r.start, relaxed);
    s.end.store(r.end, relaxed);
    s.frame.store(r.frame, relaxed);
    head_.store(h + 1, std::memory_order_release);
  }
  /** Any thread: the firings kept, oldest first, none that the writer overwrote while they were read. */
  std::vector<TraceRecord> read() const;
  std::size_t capacity() const { return mask_ + 1; }

 private:
  struct Slot {
    std::atomic<std::uint64_t> node{0};
    std::atomic<std::int64_t> start{0}, end{0}, frame{0};
  };
  std::unique_ptr<Slot[]> slots_;
  std::size_t mask_;
  std::atomic<std::uint64_t> head_{0};  // firings written so far
};

}  // namespace detail
}  // namespace apex
