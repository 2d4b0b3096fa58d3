#include "ticks.hpp"

#include <atomic>
#include <thread>

namespace apex {
namespace detail {
namespace {

using Clock = std::chrono::steady_clock;

struct Origin {
  Clock::time_point time = Clock::now();
  std::int64_t tick = ticks();
};
const Origin kOrigin;  // at load time
std::atomic<double> g_cached{0.0};

}  // namespace

double nsPerTickCached() {
  const double cached = g_cached.load(std::memory_order_relaxed);
  return cached > 0 ? cached : nsPerTick();
}

double nsPerTick() {
#if defined(__x86_64__) || defined(__i386__)
  // The longer since the origin, the more exact; the first 10 ms are waited out once.
  auto elapsed = Clock::now() - kOrigin.time;
  if (elapsed < std::chrono::milliseconds(10)) std::this_thread::sleep_for(std::chrono::milliseconds(10) - elapsed);
  const std::int64_t t = ticks();
  elapsed = Clock::now() - kOrigin.time;
  const double ns = double(std::chrono::duration_cast<std::chrono::nanoseconds>(elapsed).count());
  const double per_tick = t > kOrigin.tick ? ns / double(t - kOrigin.tick) : 1.0;
  g_cached.store(per_tick, std::memory_order_relaxed);
  return per_tick;
#else
  return 1.0;
#endif
}

}  // namespace detail
}  // namespace apex
