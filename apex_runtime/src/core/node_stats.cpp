// A node's profile (NodeState::stats): firing counts and times, their percentiles, the latency
// from its frames' stamps, dropped frames. The group thread records; any thread reads.
#include <algorithm>
#include <chrono>

#include "node_state.hpp"

namespace apex {
namespace detail {

void NodeState::recordTimedOrNothing(bool timed, std::int64_t t) {
  const auto relaxed = std::memory_order_relaxed;
  if (!timed) --untimed_left_;
  if (!last_had_data_) {  // only Nothing in and out: counted apart, not in the rate or the times
    nothing_firings_.store(nothing_firings_.load(relaxed) + 1, relaxed);
    return;
  }
  firings_.store(firings_.load(relaxed) + 1, relaxed);
  if (frame_ > 0)  // every firing with a frame: a wall-clock read (~25 ns) beside what a stamped frame costs
    recordLatency(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count());
  if (!timed) return;
  untimed_left_ = t >= kSlowTicks ? 0 : kTimeEvery - 1;
  timed_firings_.store(timed_firings_.load(relaxed) + 1, relaxed);
  time_hist_.add(static_cast<std::int64_t>(double(t) * nsPerTickCached()));
  last_t_.store(t, relaxed);
  total_t_.store(total_t_.load(relaxed) + t, relaxed);
  if (t > max_t_.load(relaxed)) max_t_.store(t, relaxed);
}

void NodeState::recordLatency(std::int64_t wall_ns) {
  const std::int64_t latency = wall_ns - frame_;
  // a stamp from another time (a bag played at its recorded stamps, simulated time): not live
  if (latency < 0 || latency > kLiveFrameNs) return;
  const auto relaxed = std::memory_order_relaxed;
  latency_hist_.add(latency);
  latency_total_.store(latency_total_.load(relaxed) + latency, relaxed);
  latency_count_.store(latency_count_.load(relaxed) + 1, relaxed);
  for (auto& out : outputs_) {  // the outputs this firing sent on
    const std::uint64_t sent = out.sent.get();
    if (sent == out.latency_seen) continue;
    out.latency_seen = sent;
    if (!out.latency) {
      auto made = std::make_shared<OutputLatency>();
      auto lock = shared_.lock();  // stats() reads it from another thread
      out.latency = std::move(made);
    }
    out.latency->hist.add(latency);
  }
}

namespace {
/** p50, p95 and max of a window of latencies into `s`, if it holds any. */
template <class Stats>
void fillLatency(const HistogramCounts& window, Stats& s) {
  const std::uint64_t frames = window.total();
  if (frames == 0) return;
  s.latency_frames = frames;
  s.latency_p50_ns = static_cast<std::int64_t>(window.quantileNs(0.5));
  s.latency_p95_ns = static_cast<std::int64_t>(window.quantileNs(0.95));
  s.latency_max_ns = static_cast<std::int64_t>(window.quantileNs(1.0));
}
}  // namespace

void NodeState::fillDistributions(NodeStats& s, std::array<Reading, 2>& window) const {
  const auto now = std::chrono::steady_clock::now();
  Reading r{time_hist_.read(), latency_hist_.read(), latency_total_.load(std::memory_order_relaxed),
            latency_count_.load(std::memory_order_relaxed), now};
  if (window[1].at == std::chrono::steady_clock::time_point{}) window[0] = window[1] = Reading{{}, {}, 0, 0, now};
  const bool step = now - window[1].at >= kWindowStep;
  if (step) window = {window[1], r};  // the window: 5 to 10 s
  s.outputs.reserve(outputs_.size());
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    s.outputs.push_back({manifest().outputs[i].name, outputs_[i].sent.get()});
    if (!outputs_[i].latency) continue;  // no live frame sent on it yet
    OutputLatency& l = *outputs_[i].latency;
    const HistogramCounts counts = l.hist.read();
    if (step) l.base = l.newer, l.newer = counts;
    fillLatency(counts.since(l.base), s.outputs.back());
  }
  const Reading& base = window[0];
  const HistogramCounts time = r.time.since(base.time), latency = r.latency.since(base.latency);
  // (a bucket's middle may lie above the largest time measured: never shown above it)
  s.p50_ns = std::min(static_cast<std::uint64_t>(time.quantileNs(0.5)), s.max_ns);
  s.p95_ns = std::min(static_cast<std::uint64_t>(time.quantileNs(0.95)), s.max_ns);
  const std::uint64_t frames = r.latency_count - base.latency_count;
  if (frames == 0) return;
  fillLatency(latency, s);
  s.latency_frames = frames;
  s.latency_mean_ns = (r.latency_total - base.latency_total) / static_cast<std::int64_t>(frames);
}

std::uint64_t NodeState::meanNs() const {
  const std::uint64_t timed = timed_firings_.load(std::memory_order_relaxed);
  return timed ? ticksToNs(total_t_.load(std::memory_order_relaxed)) / timed : 0;
}

NodeStats NodeState::stats() const {
  NodeStats s;
  s.name = name_;
  s.firings = firings_.load(std::memory_order_relaxed);
  s.nothing_firings = nothing_firings_.load(std::memory_order_relaxed);
  s.dropped = dropped_.load(std::memory_order_relaxed);
  s.last_ns = ticksToNs(last_t_.load(std::memory_order_relaxed));
  s.max_ns = ticksToNs(max_t_.load(std::memory_order_relaxed));
  s.mean_ns = meanNs();
  s.timed_firings = timed_firings_.load(std::memory_order_relaxed);
  s.timed_ns = ticksToNs(total_t_.load(std::memory_order_relaxed));
  auto shared = shared_.lock();
  s.error = shared->error;
  s.enabled = shared->enabled && shared->outer_enabled;
  fillDistributions(s, shared->window);
  return s;
}

namespace {
std::vector<HistogramBucket> bars(const HistogramCounts& h) {
  std::vector<HistogramBucket> out;
  for (int b = 0; b < HistogramCounts::kBuckets; ++b)
    if (h.counts[b] > 0) out.push_back({HistogramCounts::lowerNs(b), HistogramCounts::upperNs(b), h.counts[b]});
  return out;
}
}  // namespace

NodeProfile NodeState::profile() const {
  NodeProfile p;
  p.name = name_;
  const auto now = std::chrono::steady_clock::now();
  auto shared = shared_.lock();
  const bool windowed = shared->window[0].at != std::chrono::steady_clock::time_point{};
  const Reading none{};
  const Reading& base = windowed ? shared->window[0] : none;
  p.window_s = std::chrono::duration<double>(now - (windowed ? base.at : added_at_)).count();
  p.time = bars(time_hist_.read().since(base.time));
  p.latency = bars(latency_hist_.read().since(base.latency));
  p.firings = firings_.load(std::memory_order_relaxed);
  p.timed_firings = timed_firings_.load(std::memory_order_relaxed);
  p.timed_ns = ticksToNs(total_t_.load(std::memory_order_relaxed));
  return p;
}

}  // namespace detail
}  // namespace apex
