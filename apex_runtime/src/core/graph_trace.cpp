// The frame trace (Graph::setTracing, Graph::trace): each thread group's ring (trace_ring.hpp),
// read and named.
#include <algorithm>
#include <chrono>
#include <cstdint>

#include "apex/core/limits.hpp"
#include "graph_impl.hpp"
#include "node_state.hpp"
#include "ticks.hpp"

namespace apex {

void Graph::setTracing(bool on) {
  Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  impl.tracing_ = on;
  for (auto& [name, g] : impl.groups_) g->setTracing(on, kTraceFirings);
}

bool Graph::tracing() const {
  auto lock = impl_->lockEdits();
  return impl_->tracing_;
}

Trace Graph::trace(double seconds) const {
  const Impl& impl = *impl_;
  auto lock = impl.lockEdits();
  const std::int64_t now = detail::ticks();
  const auto wall_now = std::chrono::system_clock::now().time_since_epoch();
  const std::int64_t since = seconds > 0 ? now - static_cast<std::int64_t>(seconds * 1e9 / detail::nsPerTick()) : INT64_MIN;
  std::vector<std::pair<std::string, std::vector<detail::TraceRecord>>> kept;
  std::int64_t zero = now;
  for (auto& [name, g] : impl.groups_) {
    if (!g->traceRing()) continue;
    auto records = g->traceRing()->read();
    records.erase(std::remove_if(records.begin(), records.end(), [&](const auto& r) { return r.end < since; }), records.end());
    for (const auto& r : records) zero = std::min(zero, r.start);
    if (!records.empty()) kept.emplace_back(name, std::move(records));
  }
  Trace t;
  t.start_wall_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(wall_now).count() - detail::ticksToNs(now - zero);
  for (auto& [name, records] : kept) {
    TraceGroup& g = t.groups.emplace_back();
    g.name = name;
    for (const auto& r : records) {
      auto it = impl.order_.find(r.node & ~detail::TraceRecord::kStartsFrame);
      const bool here = it != impl.order_.end();
      g.firings.push_back({here ? it->second->name() : "(removed)", here && it->second->type() ? it->second->type()->id : "",
                           detail::ticksToNs(r.start - zero), detail::ticksToNs(r.end - zero), r.frame,
                           (r.node & detail::TraceRecord::kStartsFrame) != 0});
    }
  }
  return t;
}

}  // namespace apex
