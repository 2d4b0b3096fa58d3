#include "apex/core/histogram.hpp"

namespace apex {

int HistogramCounts::bucket(std::int64_t ns) {
  if (ns < 1024) return 0;
  const std::uint64_t v = static_cast<std::uint64_t>(ns) >> 10;  // ~µs
  if (v < static_cast<std::uint64_t>(kSub)) return static_cast<int>(v);
  const int octave = 63 - __builtin_clzll(v);  // >= 3: v in [2^octave, 2^(octave+1))
  const int sub = static_cast<int>((v >> (octave - 3)) - kSub);  // 0..7
  const int b = kSub + (octave - 3) * kSub + sub;
  return b < kBuckets ? b : kBuckets - 1;
}

double HistogramCounts::middleNs(int b) {
  if (b < kSub) return (b + 0.5) * 1024.0;
  const int octave = 3 + (b - kSub) / kSub, sub = (b - kSub) % kSub;
  const double low = double(kSub + sub) * double(1ull << (octave - 3));
  return (low + 0.5 * double(1ull << (octave - 3))) * 1024.0;
}

double HistogramCounts::lowerNs(int b) {
  if (b == 0) return 0;
  return 2 * middleNs(b) - upperNs(b);
}

double HistogramCounts::upperNs(int b) {
  if (b < kSub) return (b + 1) * 1024.0;
  const int octave = 3 + (b - kSub) / kSub;
  return middleNs(b) + 0.5 * double(1ull << (octave - 3)) * 1024.0;
}

std::uint64_t HistogramCounts::total() const {
  std::uint64_t n = 0;
  for (auto c : counts) n += c;
  return n;
}

HistogramCounts HistogramCounts::since(const HistogramCounts& earlier) const {
  HistogramCounts d;
  for (int b = 0; b < kBuckets; ++b) d.counts[b] = counts[b] >= earlier.counts[b] ? counts[b] - earlier.counts[b] : 0;
  return d;
}

double HistogramCounts::quantileNs(double q) const {
  const std::uint64_t n = total();
  if (n == 0) return 0;
  const double rank = q * double(n);
  std::uint64_t seen = 0;
  for (int b = 0; b < kBuckets; ++b) {
    seen += counts[b];
    if (double(seen) >= rank && counts[b] > 0) return middleNs(b);
  }
  return middleNs(kBuckets - 1);
}

HistogramCounts Histogram::read() const {
  HistogramCounts r;
  for (int b = 0; b < HistogramCounts::kBuckets; ++b) r.counts[b] = counts_[b].load(std::memory_order_relaxed);
  return r;
}

}  // namespace apex
