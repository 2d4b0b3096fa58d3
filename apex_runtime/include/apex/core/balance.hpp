// Balance (issue #37): thread groups that make a graph a pipeline filling the cores. Scheduling has
// no queues (DESIGN.md "The firing rule without queues"): a chain cut into k groups is a k-stage
// pipeline whose frame period is its slowest stage. So balance cuts the nodes, in a topological
// order, into at most G contiguous stages minimising the slowest one (linear partition), and
// names the edges that cross a cut beside a longer path: those serialise the groups unless a
// Relay holds their message (docs/benchmarks.md, "The demo pipeline").
// ROS-free: the runtime's ~balance service, the benchmark and the tests call it.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "apex/core/description.hpp"
#include "apex/core/result.hpp"

namespace apex {

class Graph;

/** @brief One node as balance sees it: its path and its measured time per frame. */
struct BalanceNode {
  std::string name;
  double time_ns = 0;
};

/** @brief A data connection between two nodes, by their index in the node list. Parameter and
 *  event connections are not edges here: they go through a mailbox and hold no sender back. */
struct BalanceEdge {
  std::size_t from = 0, to = 0;
};

/** @brief The nodes and data edges of a graph, as balance takes them. */
struct BalanceInput {
  std::vector<BalanceNode> nodes;
  std::vector<BalanceEdge> edges;
};

struct BalanceOptions {
  std::size_t groups = 2;  ///< at most this many stages (cores); 0 is refused
  /** What one group boundary costs each of the two stages beside it per frame: a cross-group
   *  push wakes the other group's thread (~21 µs on the benchmark machine, docs/benchmarks.md). */
  double hop_ns = 21000;
};

/** @brief An edge that crosses a cut while a longer path joins its two nodes: its receiver takes
 *  the message only once that path's work is done, and until then its sender cannot fire again. */
struct SkipEdge {
  std::size_t from = 0, to = 0;
  double span_ns = 0;  ///< the longest path's time from the sender to the receiver (receiver excluded)
  bool limits = false;  ///< its span exceeds the slowest stage: it sets the period
};

/** @brief Thread groups proposed for a graph, and what they are expected to give. */
struct Proposal {
  std::vector<std::size_t> order;  ///< the node indices in the topological order that was cut
  std::vector<std::size_t> stage;  ///< per node (by input index): its stage, 0-based along the order
  std::vector<double> stage_ns;  ///< per stage: its nodes' times plus its boundaries' hop cost
  double period_ns = 0;  ///< expected time per frame: the slowest stage, or a limiting skip edge's span
  double one_group_ns = 0;  ///< every node in one group: the sum of the times
  double speedup = 1;  ///< one_group_ns / period_ns (1 when both are 0)
  std::vector<SkipEdge> skips;
  std::vector<std::string> notes;  ///< for a person: the skip edges and what to do about them
};

/** @brief Cuts the nodes, in a topological order of the edges, into at most `options.groups`
 *  contiguous stages with the shortest period (exact: a bisection over the period with a greedy
 *  cut, which is optimal for contiguous stages). A cut that an edge with a longer span than the
 *  period crosses is avoided, or, when crossing it still gives the shortest period, kept and
 *  reported as limiting. An error names a bad edge, a data cycle, or zero groups. */
Result<Proposal> balance(const BalanceInput& input, const BalanceOptions& options);

/** @brief The same, by trying every placement of at most `groups - 1` cuts in the same order
 *  (for tests and benchmarks: exponential in the groups). */
Result<Proposal> balanceExhaustive(const BalanceInput& input, const BalanceOptions& options);

/** @brief A thread group name per stage: each stage keeps the group most of its nodes are in now
 *  (`current`, by node index) if no earlier stage took it, else "stage<k>" (k from 1), made unique. */
std::vector<std::string> stageGroupNames(const Proposal& proposal, const std::vector<std::string>& current);

/** @brief The proposal in one line for a person: stages, their times, the expected speed-up. */
std::string describeProposal(const Proposal& proposal, const BalanceInput& input, const std::vector<std::string>& group_names);

/** @brief Per node of `after`: its mean time over the firings since `before` (frames that took
 *  or sent a message), or its mean so far if `before` has no later count of it. */
std::vector<BalanceNode> measuredTimes(const std::vector<NodeStats>& before, const std::vector<NodeStats>& after);

/** @brief The graph's nodes (with `times`, by name; 0 for a node not in it) and its data edges:
 *  connections from an output into an input of the nodes that run (subgraph ports resolved). */
BalanceInput balanceInput(const Graph& graph, const std::vector<BalanceNode>& times);

// ---------------------------------------------------------------- trials
// The expected period comes from each node's time measured in the groups of the moment; a node
// that reads a frame another core made, or two stages that share the memory bus, can take longer
// than that. So the proposals that come close are run, a few frames each, and the fastest kept
// (docs/benchmarks.md, "Balance: the demo chain placed by it": there the best expected cut was
// 5% slower than the cut one node later).

/** @brief Proposals worth a trial: the best, then the placements with one of its cuts moved by
 *  one or two places, by expected period; at most `count`, none expected slower than the best by
 *  more than the fraction `within`. (Two places, and 25%: on the demo the cut two nodes later than
 *  the best expected one, expected 13-15% slower, was in some runs the fastest; docs/benchmarks.md.) */
std::vector<Proposal> balanceCandidates(const BalanceInput& input, const BalanceOptions& options, std::size_t count = 3,
                                        double within = 0.25);

struct TrialOptions {
  int frames = 100;  ///< measured per placement, after `warmup` frames in it
  int warmup = 5;
  double timeout_s = 30;  ///< per wait for frames
  /** No node fired for this long: no frames are arriving. Refused before a wait (at once), and
   *  a wait ends when they stop for this long. */
  double stopped_s = 3;
  std::function<bool()> keep_going;  ///< false stops a wait (e.g. ROS shuts down); empty: never
};

/** @brief Waits until every node that runs (enabled, no error, not waiting for anything in
 *  `before`) has fired `frames` more times than in `before`; the stats then. Refused at once if
 *  none runs or none has fired for `stopped_s`; an error names the nodes behind, with the frames
 *  each did fire. Reads the counts every 5 ms. */
Result<std::vector<NodeStats>> waitForFirings(const Graph& graph, const std::vector<NodeStats>& before, int frames,
                                              const TrialOptions& options);

/** @brief Each node of `input`'s thread group now, by node index, nodes in subgraphs too (by path, as
 *  balanceInput names them); "default" for one not in the graph. */
std::vector<std::string> currentGroups(const Graph& graph, const BalanceInput& input);

/** @brief Node name -> thread group for `proposal`, its stages named `group_names` (stageGroupNames). */
std::map<std::string, std::string> placementOf(const Proposal& proposal, const BalanceInput& input,
                                               const std::vector<std::string>& group_names);

/** @brief Runs the graph in each candidate's thread groups in turn (its stages named by
 *  stageGroupNames from the groups now) and measures its frames/s: the fewest new firings of a
 *  node that runs, per second, over `options.frames` frames after `options.warmup`. The groups are
 *  as they were afterwards, also on an error. */
Result<std::vector<double>> tryPlacements(Graph& graph, const BalanceInput& input, const std::vector<Proposal>& candidates,
                                          const TrialOptions& options);

/** @brief Balance's close proposals and what each ran in a trial. */
struct Trials {
  std::vector<Proposal> candidates;  ///< balanceCandidates: the first is balance's own
  std::vector<double> fps;  ///< per candidate, by tryPlacements; empty when fewer than two (nothing to choose)
  std::size_t fastest = 0;  ///< the index of the most frames/s (0 when none ran)
};

/** @brief balanceCandidates (at most `count`), each run by tryPlacements when there are two or
 *  more, and the fastest of them. */
Result<Trials> tryCandidates(Graph& graph, const BalanceInput& input, const BalanceOptions& options, std::size_t count,
                             const TrialOptions& options_trial);

}  // namespace apex
