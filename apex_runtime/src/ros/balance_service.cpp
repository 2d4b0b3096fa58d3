#include "balance_service.hpp"

#include <apex/Balance.h>
#include <ros/ros.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "apex/core/balance.hpp"
#include "request_text.hpp"

namespace apex {
namespace ros_host {
namespace {

/** How long ~balance waits for its frames: a slow graph's N frames, and not forever. */
constexpr double kMeasureTimeoutS = 30;

TrialOptions trialOptions(int frames, const std::atomic<bool>& stopping) {
  TrialOptions o;
  o.frames = frames;
  o.timeout_s = kMeasureTimeoutS;
  o.keep_going = [&stopping] { return ros::ok() && !stopping.load(); };
  return o;
}

/** Each node's time per frame: over `frames` new frames, or (0) as measured so far. */
Result<std::vector<BalanceNode>> nodeTimes(const Graph& graph, int frames, const std::atomic<bool>& stopping) {
  const auto before = graph.nodeStats(1.0);  // stalled for a second: not waited for
  if (frames == 0) return measuredTimes({}, before);
  if (graph.paused())
    return Status::error("the graph is paused: resume it to measure, or ask with frames 0 for the times measured so far");
  auto after = waitForFirings(graph, before, frames, trialOptions(frames, stopping));
  if (!after) return Status::error(after.message() + "; ask with frames 0 to use the times measured so far");
  return measuredTimes(before, after.value());
}

/** Of balance's close proposals, the one that ran the most frames/s over `frames` frames each
 *  (none: the first, balance's own), and the trials in words for the message. */
Result<std::pair<std::optional<Proposal>, std::string>> fastest(Graph& graph, const BalanceInput& input,
                                                                const BalanceOptions& options, const Balance::Request& req,
                                                                const std::atomic<bool>& stopping) {
  auto trials = tryCandidates(graph, input, options, std::size_t(req.trials), trialOptions(req.frames, stopping));
  if (!trials) return Status::error("cannot try the proposals: " + trials.message());
  const auto& fps = trials->fps;
  if (fps.empty()) return std::make_pair(std::optional<Proposal>(), std::string());
  char text[160];
  std::snprintf(text, sizeof text,
                "; tried the %zu closest placements for %d frames each: %.1f to %.1f frames/s, kept the fastest", fps.size(),
                req.frames, *std::min_element(fps.begin(), fps.end()), fps[trials->fastest]);
  std::optional<Proposal> chosen;
  if (trials->fastest > 0) chosen = std::move(trials->candidates[trials->fastest]);
  return std::make_pair(std::move(chosen), std::string(text));
}

/** Moves each node whose group differs from `now` (by index, as res.nodes); all or nothing: a
 *  refused move moves the others back. */
Status applyGroups(const Balance::Response& res, const std::vector<std::string>& now,
                   const std::function<bool(SetThreadGroup::Request&, SetThreadGroup::Response&)>& set_group) {
  std::vector<std::pair<std::string, std::string>> moved;  // node, its old group
  auto move = [&](const std::string& node, const std::string& group) {
    SetThreadGroup::Request req;
    SetThreadGroup::Response out;
    req.node = node, req.group = group;
    set_group(req, out);
    return out.success ? Status::ok() : Status::error("cannot move " + node + " to group " + group + ": " + out.message);
  };
  for (std::size_t i = 0; i < res.nodes.size(); ++i) {
    const std::string& was = now[i];
    if (was == res.groups[i]) continue;
    if (auto st = move(res.nodes[i], res.groups[i]); !st) {
      for (auto it = moved.rbegin(); it != moved.rend(); ++it) (void)move(it->first, it->second);
      return Status::error(st.message() + " (the nodes moved before it are back in their groups)");
    }
    moved.emplace_back(res.nodes[i], was);
  }
  return Status::ok();
}

Status answerBalance(Graph& graph, const Balance::Request& req, Balance::Response& res, const BalanceService::SetGroup& set_group,
                     const std::atomic<bool>& stopping) {
  if (req.frames < 0) return Status::error("frames must be 0 (the times measured so far) or more");
  if (req.groups < 0) return Status::error("groups must be 0 (the number of cores) or more");
  BalanceOptions options;
  options.groups = req.groups > 0 ? std::size_t(req.groups) : std::max(1u, std::thread::hardware_concurrency());
  auto times = nodeTimes(graph, req.frames, stopping);
  if (!times) return times.status();
  const BalanceInput input = balanceInput(graph, times.value());
  auto proposal = balance(input, options);
  if (!proposal) return Status::error("cannot balance: " + proposal.message());
  std::string tried;
  if (req.trials > 1 && req.frames > 0) {  // the close proposals run, the fastest kept
    auto chosen = fastest(graph, input, options, req, stopping);
    if (!chosen) return chosen.status();
    if (chosen->first) proposal = std::move(*chosen->first);
    tried = chosen->second;
  }
  const std::vector<std::string> current = currentGroups(graph, input);
  const Proposal& p = proposal.value();
  res.stage_groups = stageGroupNames(p, current);
  for (std::size_t i = 0; i < input.nodes.size(); ++i) {
    res.nodes.push_back(input.nodes[i].name);
    res.groups.push_back(res.stage_groups[p.stage[i]]);
  }
  for (double ns : p.stage_ns) res.stage_ms.push_back(ns * 1e-6);
  res.expected_speedup = p.speedup;
  res.notes = p.notes;
  res.message = describeProposal(p, input, res.stage_groups) + tried;
  return req.apply ? applyGroups(res, current, set_group) : Status::ok();
}

}  // namespace

BalanceService::BalanceService(ros::NodeHandle& pnh, Graph& graph, SetGroup set_group) {
  auto handle = [this, &graph, set_group](Balance::Request& req, Balance::Response& res) {
    const Status st = answerBalance(graph, req, res, set_group, stopping_);
    res.success = st.isOk();
    if (!st) res.message = st.message();
    return true;  // the call itself worked; `success` says whether balancing did
  };
  server_ = advertiseChecked<Balance::Request, Balance::Response>(pnh, "balance", handle, &queue_);
  spinner_ = std::make_unique<ros::AsyncSpinner>(1, &queue_);  // one at a time: two applies would undo each other's moves
  spinner_->start();
}

BalanceService::~BalanceService() {
  stopping_ = true;  // a balance waiting for frames ends now
  server_.shutdown();
  spinner_->stop();
}

}  // namespace ros_host
}  // namespace apex
