// Balance's trials: the close proposals run a few frames each, the fastest kept (balance.hpp).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <thread>

#include "apex/core/balance.hpp"
#include "apex/core/graph.hpp"

namespace apex {
namespace {

using Clock = std::chrono::steady_clock;

/** The nodes that run, by name: enabled, without an error, not waiting for anything. */
std::map<std::string, std::uint64_t> runningFirings(const std::vector<NodeStats>& stats) {
  std::map<std::string, std::uint64_t> out;
  for (const auto& s : stats)
    if (s.enabled && s.error.empty() && s.waiting_for.empty()) out[s.name] = s.firings;
  return out;
}

/** The fewest firings a node of `from` made since then, in `now`. */
std::uint64_t fewestSince(const std::map<std::string, std::uint64_t>& from, const std::vector<NodeStats>& now) {
  std::uint64_t fewest = ~std::uint64_t(0);
  for (const auto& s : now)
    if (auto it = from.find(s.name); it != from.end()) fewest = std::min(fewest, s.firings - std::min(s.firings, it->second));
  return from.empty() ? 0 : fewest;
}

/** Moves each node to its group in `groups` (node name -> group); the first refusal is the error. */
Status place(Graph& graph, const std::map<std::string, std::string>& groups) {
  for (const auto& [node, group] : groups)
    if (auto st = graph.setThreadGroup(node, group); !st) return st;
  return Status::ok();
}

}  // namespace

Result<std::vector<NodeStats>> waitForFirings(const Graph& graph, const std::vector<NodeStats>& before, int frames,
                                              const TrialOptions& options) {
  const auto from = runningFirings(before);
  auto seconds = [](double s) { return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s)); };
  auto text = [](double s) {
    char t[32];
    std::snprintf(t, sizeof t, "%g s", s);
    return std::string(t);
  };
  if (from.empty()) return Status::error("cannot measure: no node runs (each is disabled, failing or waiting for data)");
  double idle = 1e300;
  for (const auto& s : before)
    if (from.count(s.name)) idle = std::min(idle, s.idle_s);
  if (idle >= options.stopped_s)
    return Status::error("cannot measure: no frames are arriving (no node fired in the last " + text(idle) + ")");
  const auto deadline = Clock::now() + seconds(options.timeout_s);
  auto progress = Clock::now();
  std::uint64_t total = 0;
  while (true) {
    auto now = graph.nodeStats(1e12);  // no stall check: only the counts are wanted
    if (fewestSince(from, now) >= std::uint64_t(frames)) return now;
    std::uint64_t fired = 0;
    for (const auto& s : now)
      if (from.count(s.name)) fired += s.firings;
    if (fired != total) total = fired, progress = Clock::now();
    const bool stopped = Clock::now() - progress > seconds(options.stopped_s);
    if (stopped || Clock::now() > deadline || (options.keep_going && !options.keep_going())) {
      std::string behind;
      for (const auto& s : now)
        if (auto it = from.find(s.name); it != from.end() && s.firings < it->second + std::uint64_t(frames))
          behind += (behind.empty() ? "" : ", ") + s.name + " (" + std::to_string(s.firings - it->second) + ")";
      const std::string why = stopped ? "the frames stopped: no node fired for " + text(options.stopped_s) + ", and "
                                      : "within " + text(options.timeout_s) + " ";
      return Status::error("cannot measure: " + why + "these nodes did not fire " + std::to_string(frames) +
                           " more frames (the frames each did fire): " + behind);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));  // the graph has no event to wait on
  }
}

namespace {

/** Each node's thread group by its path ("sub/inner" inside a subgraph), into `out`. */
void groupsByPath(const GraphDescription& d, const std::string& prefix, std::map<std::string, std::string>& out) {
  for (const auto& n : d.nodes) {
    const std::string path = prefix.empty() ? n.name : prefix + "/" + n.name;
    out[path] = n.thread_group;
    if (n.subgraph) groupsByPath(*n.subgraph, path, out);
  }
}

std::vector<std::string> groupsOf(const GraphDescription& d, const BalanceInput& input) {
  std::map<std::string, std::string> now;
  groupsByPath(d, "", now);
  std::vector<std::string> out;
  for (const auto& n : input.nodes) out.push_back(now.count(n.name) ? now[n.name] : kDefaultGroup);
  return out;
}

}  // namespace

std::vector<std::string> currentGroups(const Graph& graph, const BalanceInput& input) {
  return groupsOf(graph.describe(), input);
}

std::map<std::string, std::string> placementOf(const Proposal& proposal, const BalanceInput& input,
                                               const std::vector<std::string>& group_names) {
  std::map<std::string, std::string> out;
  for (std::size_t i = 0; i < input.nodes.size(); ++i) out[input.nodes[i].name] = group_names[proposal.stage[i]];
  return out;
}

Result<std::vector<double>> tryPlacements(Graph& graph, const BalanceInput& input, const std::vector<Proposal>& candidates,
                                          const TrialOptions& options) {
  const GraphDescription before = graph.describe();
  const std::vector<std::string>& groups_before = before.thread_groups;
  const std::vector<std::string> current = groupsOf(before, input);
  std::set<std::string> trial_groups;
  std::vector<double> fps;
  Status failed = Status::ok();
  for (const Proposal& p : candidates) {
    const auto names = stageGroupNames(p, current);
    trial_groups.insert(names.begin(), names.end());
    if (failed = place(graph, placementOf(p, input, names)); !failed) break;
    auto warm = waitForFirings(graph, graph.nodeStats(1.0), options.warmup, options);
    if (!warm) {
      failed = warm.status();
      break;
    }
    const auto t0 = Clock::now();
    auto done = waitForFirings(graph, warm.value(), options.frames, options);
    if (!done) {
      failed = done.status();
      break;
    }
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    fps.push_back(s > 0 ? double(fewestSince(runningFirings(warm.value()), done.value())) / s : 0.0);
  }
  std::map<std::string, std::string> back;
  for (std::size_t i = 0; i < input.nodes.size(); ++i) back[input.nodes[i].name] = current[i];
  const Status restored = place(graph, back);
  // The groups the trials made go again (one a node left a timer in stays, empty: refused then).
  for (const auto& name : trial_groups)
    if (restored && name != kDefaultGroup && std::find(groups_before.begin(), groups_before.end(), name) == groups_before.end())
      (void)graph.removeThreadGroup(name);
  if (!failed) return failed;
  if (!restored) return Status::error("cannot put the nodes back in their groups after the trials: " + restored.message());
  return fps;
}

Result<Trials> tryCandidates(Graph& graph, const BalanceInput& input, const BalanceOptions& options, std::size_t count,
                             const TrialOptions& options_trial) {
  Trials out;
  out.candidates = balanceCandidates(input, options, count);
  if (out.candidates.size() < 2) return out;
  auto fps = tryPlacements(graph, input, out.candidates, options_trial);
  if (!fps) return fps.status();
  out.fps = std::move(fps.value());
  out.fastest = std::size_t(std::max_element(out.fps.begin(), out.fps.end()) - out.fps.begin());
  return out;
}

}  // namespace apex
