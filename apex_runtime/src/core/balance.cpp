// Balance: the linear partition of a topological order into pipeline stages (balance.hpp).
#include "apex/core/balance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <set>

#include "apex/core/graph.hpp"
#include "apex/core/manifest.hpp"

namespace apex {
namespace {

/** The input checked and prepared once: order, positions, out-edges and each edge's span. */
struct Prepared {
  std::vector<double> t;  // by node index
  std::vector<std::size_t> order, pos;  // pos[node] = its place in order
  std::vector<std::vector<std::size_t>> out;  // node -> receivers
  std::vector<double> span;  // by edge index
  std::vector<double> prefix;  // prefix[i]: the times of the first i nodes of the order
  double total = 0;
};

/** Kahn's algorithm taking the ready node of the lowest index first: a chain keeps its order,
 *  and a side branch (a Relay) comes as late as its receiver allows. */
Result<std::vector<std::size_t>> topologicalOrder(const Prepared& p, const BalanceInput& in) {
  const std::size_t n = in.nodes.size();
  std::vector<std::size_t> missing(n, 0);
  for (const auto& e : in.edges) ++missing[e.to];
  std::set<std::size_t> ready;
  for (std::size_t i = 0; i < n; ++i)
    if (missing[i] == 0) ready.insert(i);
  std::vector<std::size_t> order;
  while (!ready.empty()) {
    const std::size_t x = *ready.begin();
    ready.erase(ready.begin());
    order.push_back(x);
    for (std::size_t y : p.out[x])
      if (--missing[y] == 0) ready.insert(y);
  }
  if (order.size() == n) return order;
  for (std::size_t i = 0; i < n; ++i)
    if (missing[i] > 0) return Status::error("the data connections make a cycle through '" + in.nodes[i].name + "'");
  return Status::error("the data connections make a cycle");
}

/** Per edge u -> v: the longest path's time from u to v, v's own excluded. Every path from u to v
 *  lies between their places in the order, so only that window is walked. */
void computeSpans(Prepared& p, const BalanceInput& in) {
  const std::size_t n = in.nodes.size();
  std::vector<double> longest(n, -1);  // -1: not reached from the sender
  p.span.assign(in.edges.size(), 0);
  std::map<std::size_t, std::vector<std::size_t>> by_sender;  // sender -> its edges
  for (std::size_t i = 0; i < in.edges.size(); ++i) by_sender[in.edges[i].from].push_back(i);
  for (const auto& [u, edges] : by_sender) {
    std::size_t end = p.pos[u];
    for (std::size_t e : edges) end = std::max(end, p.pos[in.edges[e].to]);
    longest[u] = 0;
    for (std::size_t at = p.pos[u]; at < end; ++at) {
      const std::size_t x = p.order[at];
      if (longest[x] < 0) continue;
      for (std::size_t y : p.out[x]) longest[y] = std::max(longest[y], longest[x] + p.t[x]);
    }
    for (std::size_t e : edges) p.span[e] = longest[in.edges[e].to];
    for (std::size_t at = p.pos[u]; at <= end; ++at) longest[p.order[at]] = -1;
    for (std::size_t at = p.pos[u]; at < end; ++at)  // receivers beyond the window were touched too
      for (std::size_t y : p.out[p.order[at]]) longest[y] = -1;
  }
}

Result<Prepared> prepare(const BalanceInput& in, const BalanceOptions& options) {
  if (options.groups == 0) return Status::error("balance needs at least one group");
  if (!(options.hop_ns >= 0)) return Status::error("the cost of a group boundary must not be negative");
  const std::size_t n = in.nodes.size();
  Prepared p;
  p.out.resize(n);
  for (const auto& node : in.nodes) {
    if (!(node.time_ns >= 0)) return Status::error("node '" + node.name + "' has no valid time");
    p.t.push_back(node.time_ns);
    p.total += node.time_ns;
  }
  for (const auto& e : in.edges) {
    if (e.from >= n || e.to >= n) return Status::error("an edge names a node that is not in the list");
    if (e.from == e.to) return Status::error("node '" + in.nodes[e.from].name + "' feeds itself");
    p.out[e.from].push_back(e.to);
  }
  auto order = topologicalOrder(p, in);
  if (!order) return order.status();
  p.order = std::move(order.value());
  p.pos.resize(n);
  p.prefix.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) p.pos[p.order[i]] = i, p.prefix[i + 1] = p.prefix[i] + p.t[p.order[i]];
  computeSpans(p, in);
  return p;
}

/** A placement: cut c ends a stage after the node at place c of the order (ascending). */
using Cuts = std::vector<std::size_t>;

double slowestStage(const Proposal& r) {
  return r.stage_ns.empty() ? 0 : *std::max_element(r.stage_ns.begin(), r.stage_ns.end());
}

Proposal evaluate(const Prepared& p, const BalanceInput& in, const BalanceOptions& o, const Cuts& cuts) {
  Proposal r;
  r.order = p.order;
  r.one_group_ns = p.total;
  r.stage.assign(p.t.size(), 0);
  r.stage_ns.assign(p.t.empty() ? 0 : cuts.size() + 1, 0);
  std::size_t s = 0;
  for (std::size_t at = 0; at < p.order.size(); ++at) {
    r.stage[p.order[at]] = s;
    r.stage_ns[s] += p.t[p.order[at]];
    if (s < cuts.size() && cuts[s] == at) ++s;
  }
  for (std::size_t k = 0; k + 1 < r.stage_ns.size(); ++k) r.stage_ns[k] += o.hop_ns, r.stage_ns[k + 1] += o.hop_ns;
  const double slowest = slowestStage(r);
  r.period_ns = slowest;
  for (std::size_t i = 0; i < in.edges.size(); ++i) {
    const auto& e = in.edges[i];
    if (r.stage[e.from] == r.stage[e.to]) continue;
    r.period_ns = std::max(r.period_ns, p.span[i]);
    if (p.span[i] > p.t[e.from] * (1 + 1e-9) + 1e-6)  // a longer path than the edge itself
      r.skips.push_back({e.from, e.to, p.span[i], p.span[i] > slowest});
  }
  r.speedup = r.period_ns > 0 ? r.one_group_ns / r.period_ns : 1.0;
  return r;
}

/** The fewest stages with every stage within `period` and no edge of a longer span cut, by
 *  taking each stage as far as it goes (optimal for contiguous stages: no placement's k-th stage
 *  ends further); none if more than `groups` stages are needed. `spans` false: spans ignored. */
std::optional<Cuts> greedyCuts(const Prepared& p, const BalanceInput& in, const BalanceOptions& o, double period, bool spans) {
  const std::size_t n = p.order.size();
  std::vector<int> blocked(n + 1, 0);  // difference array: cuts c in [pos(u), pos(v)) are refused
  if (spans)
    for (std::size_t i = 0; i < in.edges.size(); ++i)
      if (p.span[i] > period) ++blocked[p.pos[in.edges[i].from]], --blocked[p.pos[in.edges[i].to]];
  for (std::size_t c = 1; c <= n; ++c) blocked[c] += blocked[c - 1];
  Cuts cuts;
  std::size_t s = 0;
  while (s < n) {
    const double entry = s > 0 ? o.hop_ns : 0;  // the boundary before this stage
    if (p.prefix[n] - p.prefix[s] + entry <= period) return cuts;
    if (cuts.size() + 1 >= o.groups) return std::nullopt;
    std::optional<std::size_t> last;
    for (std::size_t c = s; c + 1 < n && p.prefix[c + 1] - p.prefix[s] + entry + o.hop_ns <= period; ++c)
      if (blocked[c] == 0) last = c;
    if (!last) return std::nullopt;
    cuts.push_back(*last);
    s = *last + 1;
  }
  return cuts;
}

/** The shortest period greedyCuts reaches: bisection down to a relative 1e-12, then the period
 *  the placement found really has (a stage's time or an edge's span: the optimum itself). */
Cuts bestCuts(const Prepared& p, const BalanceInput& in, const BalanceOptions& o, bool spans) {
  Cuts best;  // one stage: always within the total
  if (auto none = greedyCuts(p, in, o, 0, spans)) return *none;
  double lo = 0, hi = p.total;
  for (int i = 0; i < 200 && hi - lo > hi * 1e-12; ++i) {
    const double mid = (lo + hi) / 2;
    if (auto c = greedyCuts(p, in, o, mid, spans)) hi = mid, best = *c;
    else lo = mid;
  }
  return best;
}

std::string ms(double ns) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f ms", ns * 1e-6);
  return b;
}

/** The skip edges `r` cuts, and, if cutting where such edges are would do better once they had a
 *  Relay (`relayed`: the best stages with spans ignored), what it could give. */
void addNotes(Proposal& r, const BalanceInput& in, const Proposal& relayed) {
  for (const SkipEdge& s : r.skips) {
    const std::string from = in.nodes[s.from].name, to = in.nodes[s.to].name;
    std::string note = "'" + from + "' -> '" + to + "' crosses from stage " + std::to_string(r.stage[s.from] + 1) +
                       " into stage " + std::to_string(r.stage[s.to] + 1) + " beside a longer path (" + ms(s.span_ns) + "): '" +
                       from + "' waits each frame until '" + to +
                       "' takes its message; a Relay (apex_nodes/Relay) on this edge frees it";
    if (s.limits) note += ". It sets the period now: " + ms(s.span_ns) + " per frame";
    r.notes.push_back(note);
  }
  const double stages_only = slowestStage(relayed);
  if (!(stages_only < r.period_ns * (1 - 1e-9))) return;
  std::string names;
  for (const SkipEdge& s : relayed.skips)
    if (s.limits) names += (names.empty() ? "'" : ", '") + in.nodes[s.from].name + "' -> '" + in.nodes[s.to].name + "'";
  char b[160];
  std::snprintf(b, sizeof b, ", %zu groups could give up to %.2fx (stages of at most %s): ", relayed.stage_ns.size(),
                relayed.one_group_ns / stages_only, ms(stages_only).c_str());
  r.notes.push_back("with a Relay on " + names + b +
                    "these edges join nodes that a longer path also joins, so cut without one they hold their senders back");
}

}  // namespace

Result<Proposal> balance(const BalanceInput& input, const BalanceOptions& options) {
  auto p = prepare(input, options);
  if (!p) return p.status();
  Proposal r = evaluate(p.value(), input, options, bestCuts(p.value(), input, options, true));
  addNotes(r, input, evaluate(p.value(), input, options, bestCuts(p.value(), input, options, false)));
  return r;
}

Result<Proposal> balanceExhaustive(const BalanceInput& input, const BalanceOptions& options) {
  auto prepared = prepare(input, options);
  if (!prepared) return prepared.status();
  const Prepared& p = prepared.value();
  std::optional<Proposal> best;
  Cuts cuts;
  // every set of at most groups-1 cuts among the n-1 places, in ascending order
  std::function<void(std::size_t)> visit = [&](std::size_t from) {
    Proposal r = evaluate(p, input, options, cuts);
    if (!best || r.period_ns < best->period_ns) best = std::move(r);
    if (cuts.size() + 1 >= options.groups) return;
    for (std::size_t c = from; c + 1 < p.order.size(); ++c) {
      cuts.push_back(c);
      visit(c + 1);
      cuts.pop_back();
    }
  };
  visit(0);
  return *best;
}

std::vector<Proposal> balanceCandidates(const BalanceInput& input, const BalanceOptions& options, std::size_t count,
                                        double within) {
  auto prepared = prepare(input, options);
  if (!prepared || count == 0) return {};
  const Prepared& p = prepared.value();
  const Cuts best = bestCuts(p, input, options, true);
  std::set<Cuts> seen{best};
  std::vector<Proposal> out{evaluate(p, input, options, best)};
  for (std::size_t k = 0; k < best.size(); ++k)
    for (int step : {-2, -1, 1, 2}) {
      Cuts c = best;
      const long at = long(c[k]) + step;
      if (at < 0 || at + 1 >= long(p.order.size())) continue;  // a cut after the last node is none
      if ((k > 0 && at <= long(c[k - 1])) || (k + 1 < c.size() && at >= long(c[k + 1]))) continue;
      c[k] = std::size_t(at);
      if (!seen.insert(c).second) continue;
      Proposal r = evaluate(p, input, options, c);
      if (r.period_ns <= out.front().period_ns * (1 + within)) out.push_back(std::move(r));
    }
  std::stable_sort(out.begin() + 1, out.end(), [](const Proposal& a, const Proposal& b) { return a.period_ns < b.period_ns; });
  if (out.size() > count) out.resize(count);
  return out;
}

std::vector<std::string> stageGroupNames(const Proposal& proposal, const std::vector<std::string>& current) {
  std::vector<std::map<std::string, std::size_t>> votes(proposal.stage_ns.size());
  for (std::size_t i = 0; i < proposal.stage.size() && i < current.size(); ++i) ++votes[proposal.stage[i]][current[i]];
  std::set<std::string> taken;
  std::vector<std::string> names;
  for (std::size_t k = 0; k < votes.size(); ++k) {
    std::string name;
    std::size_t most = 0;
    for (const auto& [group, count] : votes[k])
      if (count > most && !taken.count(group)) name = group, most = count;
    for (int i = 1; name.empty() || taken.count(name); ++i)
      name = "stage" + std::to_string(k + 1) + (i > 1 ? "_" + std::to_string(i) : "");
    taken.insert(name);
    names.push_back(name);
  }
  return names;
}

std::string describeProposal(const Proposal& r, const BalanceInput& in, const std::vector<std::string>& names) {
  std::vector<std::vector<std::string>> members(r.stage_ns.size());
  for (std::size_t x : r.order) members[r.stage[x]].push_back(in.nodes[x].name);
  std::string text = std::to_string(r.stage_ns.size()) + (r.stage_ns.size() == 1 ? " group:" : " groups:");
  for (std::size_t k = 0; k < members.size(); ++k) {
    const auto& m = members[k];
    text += std::string(k ? ", " : " ") + (k < names.size() ? names[k] : "stage" + std::to_string(k + 1)) + " [" + m.front() +
            (m.size() > 1 ? (m.size() > 2 ? " .. " : " ") + m.back() : "") + "] " + ms(r.stage_ns[k]);
  }
  char b[96];
  std::snprintf(b, sizeof b, "; expect %.2fx the frames/s of one group (%s per frame, against %s)", r.speedup,
                ms(r.period_ns).c_str(), ms(r.one_group_ns).c_str());
  return text + b;
}

std::vector<BalanceNode> measuredTimes(const std::vector<NodeStats>& before, const std::vector<NodeStats>& after) {
  std::map<std::string, const NodeStats*> old;
  for (const auto& s : before) old[s.name] = &s;
  std::vector<BalanceNode> out;
  for (const auto& s : after) {
    double t = double(s.mean_ns);
    auto it = old.find(s.name);
    if (it != old.end() && s.firings > it->second->firings) {  // the mean over the new firings only
      const double sum = double(s.mean_ns) * double(s.firings) - double(it->second->mean_ns) * double(it->second->firings);
      t = std::max(0.0, sum / double(s.firings - it->second->firings));
    }
    out.push_back({s.name, t});
  }
  return out;
}

namespace {
bool hasPort(const std::vector<PortSpec>& ports, const std::string& name) {
  return std::any_of(ports.begin(), ports.end(), [&](const PortSpec& p) { return p.name == name; });
}
}  // namespace

BalanceInput balanceInput(const Graph& graph, const std::vector<BalanceNode>& times) {
  std::map<std::string, double> time;
  for (const auto& t : times) time[t.name] = t.time_ns;
  BalanceInput in;
  std::map<std::string, std::size_t> index;
  for (const auto& s : graph.nodeStats(1e12)) {  // insertion order; no stall check wanted
    index[s.name] = in.nodes.size();
    in.nodes.push_back({s.name, time.count(s.name) ? time[s.name] : 0.0});
  }
  for (const auto& c : graph.connections()) {
    const auto from = index.find(c.from_node), to = index.find(c.to_node);
    if (from == index.end() || to == index.end()) continue;
    const auto out_iface = graph.nodeInterface(c.from_node), in_iface = graph.nodeInterface(c.to_node);
    if (out_iface && in_iface && hasPort(out_iface->outputs, c.from_port) && hasPort(in_iface->inputs, c.to_port))
      in.edges.push_back({from->second, to->second});
  }
  return in;
}

}  // namespace apex
