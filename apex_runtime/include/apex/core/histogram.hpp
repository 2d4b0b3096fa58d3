// Durations as a histogram that one thread writes without a lock and anyone reads: log-linear
// buckets, 8 per power of two (from 1.024 µs up to about 37 minutes), so a quantile read from it
// is within 1/16 of the true value. Counts only grow: a window is the difference of two readings.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

namespace apex {

/** @brief A reading of a Histogram: counts per bucket. */
struct HistogramCounts {
  static constexpr int kSub = 8;  ///< buckets per power of two
  static constexpr int kOctaves = 31;  ///< powers of two above the first kSub buckets
  static constexpr int kBuckets = kSub + kSub * kOctaves;
  std::array<std::uint64_t, kBuckets> counts{};

  /** The bucket of a duration (ns); below 1.024 µs: 0; beyond the last: the last. */
  static int bucket(std::int64_t ns);
  /** The middle of a bucket, ns. */
  static double middleNs(int bucket);
  /** A bucket's lower and upper bound, ns: it holds durations in [lower, upper). */
  static double lowerNs(int bucket);
  static double upperNs(int bucket);
  std::uint64_t total() const;
  /** What `later` counted since this reading (a window). */
  HistogramCounts since(const HistogramCounts& earlier) const;
  /** The q-quantile (0..1), ns (the middle of its bucket); 0 if nothing was counted. */
  double quantileNs(double q) const;
};

/** @brief The live histogram: add() from one thread only (relaxed load and store, no locked
 *  instruction), read() from any. */
class Histogram {
 public:
  void add(std::int64_t ns) {
    auto& c = counts_[HistogramCounts::bucket(ns)];
    c.store(c.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  }
  HistogramCounts read() const;

 private:
  std::array<std::atomic<std::uint64_t>, HistogramCounts::kBuckets> counts_{};
};

}  // namespace apex
