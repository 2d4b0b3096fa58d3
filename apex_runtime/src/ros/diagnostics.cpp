// One diagnostic status per node and per thread group. Levels, as diagnostic tools read them:
// ERROR with the node's error text; STALE for a placeholder (its type is not loaded: it never
// runs); WARN when stalled (what it waits for, as ~status says) or slower than its expected
// rate; OK otherwise, a disabled node included. Key/values: firings, rate, timing, group.
#include "diagnostics.hpp"

#include <diagnostic_msgs/DiagnosticArray.h>
#include <diagnostic_msgs/DiagnosticStatus.h>

#include <cstdio>
#include <set>

#include "convert.hpp"

namespace apex {
namespace ros_host {
namespace {

using diagnostic_msgs::DiagnosticStatus;

const std::string kNode = "node ", kGroup = "thread group ";

std::string fixed(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

}  // namespace

Diagnostics::Diagnostics(ros::NodeHandle nh, ros::NodeHandle pnh, const Graph& graph)
    : graph_(graph), updater_(nh, pnh, pnh.getNamespace()) {  // statuses named after the runtime: "apex: node threshold"
  updater_.setHardwareID("apex runtime " + pnh.getNamespace());
  XmlRpc::XmlRpcValue rates;
  if (pnh.getParam("expected_rates", rates) && rates.getType() == XmlRpc::XmlRpcValue::TypeStruct) {
    for (auto& [node, hz] : rates) {
      if (hz.getType() == XmlRpc::XmlRpcValue::TypeDouble) expected_[node] = double(hz);
      else if (hz.getType() == XmlRpc::XmlRpcValue::TypeInt) expected_[node] = int(hz);
      else ROS_ERROR_STREAM_NAMED("apex", "~expected_rates/" << node << " must be a number (Hz)");
    }
  }
  listeners_ = nh.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 1);  // the updater's, shared
  timer_ = pnh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { tick(); });
}

void Diagnostics::setGraph(const GraphState& state) {
  std::lock_guard<std::mutex> lock(mutex_);
  nodes_.clear();
  for (NodeInfo n : state.nodes) {
    if (!n.subgraph.empty()) continue;  // a subgraph's nodes speak for it
    n.parameters.clear(), n.ports.clear();
    nodes_[n.name] = std::move(n);
  }
}

void Diagnostics::tick() {
  if (listeners_.getNumSubscribers() == 0) return;  // a paused graph of 5,000 nodes spent 7% of a core on none
  const RuntimeStatus status = toStatus(graph_);
  std::lock_guard<std::mutex> lock(mutex_);
  const ros::WallTime now = ros::WallTime::now();
  const double dt = last_tick_.isZero() ? 0.0 : (now - last_tick_).toSec();
  last_tick_ = now;
  stats_.clear(), groups_.clear(), rates_.clear();
  std::set<std::string> names;
  std::map<std::string, std::uint64_t> firings;
  for (const auto& n : status.nodes) {
    const auto last = last_firings_.find(n.name);
    const bool counted = dt > 0 && last != last_firings_.end() && n.firings >= last->second;
    rates_[n.name] = counted ? double(n.firings - last->second) / dt : 0.0;
    firings[n.name] = n.firings;
    stats_[n.name] = n;
    names.insert(kNode + n.name);
  }
  last_firings_ = std::move(firings);
  for (const auto& [name, info] : nodes_) names.insert(kNode + name);  // placeholders have no statistics
  for (const auto& g : status.groups) {
    groups_[g.name] = g;
    names.insert(kGroup + g.name);
  }
  for (const auto& task : tasks_)
    if (!names.count(task)) updater_.removeByName(task);
  for (const auto& task : names) {
    if (tasks_.count(task)) continue;
    if (task.compare(0, kNode.size(), kNode) == 0) {
      const std::string node = task.substr(kNode.size());
      updater_.add(task, [this, node](diagnostic_updater::DiagnosticStatusWrapper& s) { nodeStatus(node, s); });
    } else {
      const std::string group = task.substr(kGroup.size());
      updater_.add(task, [this, group](diagnostic_updater::DiagnosticStatusWrapper& s) { groupStatus(group, s); });
    }
  }
  tasks_ = std::move(names);
  updater_.force_update();  // runs the tasks here, under our lock
}

void Diagnostics::nodeStatus(const std::string& node, diagnostic_updater::DiagnosticStatusWrapper& out) {
  const auto info = nodes_.find(node);
  if (info != nodes_.end()) {
    out.add("type", info->second.type);
    out.add("thread group", info->second.thread_group.empty() ? kDefaultGroup : info->second.thread_group);
    if (info->second.state == "placeholder") {
      out.summary(DiagnosticStatus::STALE,
                  info->second.error.empty() ? "placeholder: its type is not loaded" : info->second.error);
      return;
    }
  }
  const auto it = stats_.find(node);
  if (it == stats_.end()) return out.summary(DiagnosticStatus::STALE, "no statistics");
  const NodeStatus& n = it->second;
  const double rate = rates_[node];
  out.add("firings", n.firings);
  out.add("rate (Hz)", fixed(rate, 1));
  out.add("mean time (ms)", fixed(n.mean_ms, 3));
  out.add("max time (ms)", fixed(n.max_ms, 3));
  out.add("last time (ms)", fixed(n.last_ms, 3));
  if (n.dropped > 0) out.add("dropped frames", n.dropped);
  out.add("p50 time (ms)", fixed(n.p50_ms, 3));
  out.add("p95 time (ms)", fixed(n.p95_ms, 3));
  if (n.latency_ms >= 0) {  // from its frame's stamp to the end of its firing
    out.add("latency p50 (ms)", fixed(n.latency_p50_ms, 2));
    out.add("latency p95 (ms)", fixed(n.latency_p95_ms, 2));
    out.add("latency max (ms)", fixed(n.latency_max_ms, 2));
  }
  for (std::size_t i = 0; i < n.outputs.size() && i < n.output_latency_p50_ms.size(); ++i)
    if (n.output_latency_p50_ms[i] >= 0 && n.outputs.size() > 1)  // with one output, the node's own
      out.add("latency of '" + n.outputs[i] + "' p50 / p95 / max (ms)", fixed(n.output_latency_p50_ms[i], 2) + " / " +
                                                                            fixed(n.output_latency_p95_ms[i], 2) + " / " +
                                                                            fixed(n.output_latency_max_ms[i], 2));
  out.add("idle (s)", fixed(n.idle_s, 1));
  if (!n.waiting_for.empty()) out.add("waiting for", n.waiting_for);
  const auto expected = expected_.find(node);
  if (expected != expected_.end()) out.add("expected rate (Hz)", fixed(expected->second, 1));
  if (!n.error.empty()) return out.summary(DiagnosticStatus::ERROR, n.error);
  if (n.state == "disabled") return out.summary(DiagnosticStatus::OK, "disabled");
  if (!n.waiting_for.empty()) return out.summary(DiagnosticStatus::WARN, "stalled: " + n.waiting_for);
  if (expected != expected_.end() && rate < 0.9 * expected->second)
    return out.summary(DiagnosticStatus::WARN, "slow: " + fixed(rate, 1) + " Hz, expected " + fixed(expected->second, 1) + " Hz");
  out.summary(DiagnosticStatus::OK, "ok, " + fixed(rate, 1) + " Hz");
}

void Diagnostics::groupStatus(const std::string& group, diagnostic_updater::DiagnosticStatusWrapper& out) {
  const auto it = groups_.find(group);
  if (it == groups_.end()) return out.summary(DiagnosticStatus::STALE, "gone");
  out.add("load", fixed(it->second.load, 3));
  out.add("firings", it->second.firings);
  out.add("wake-ups", it->second.wakeups);
  out.summary(DiagnosticStatus::OK, "load " + fixed(100 * it->second.load, 0) + "%");
}

}  // namespace ros_host
}  // namespace apex
