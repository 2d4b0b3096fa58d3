#include "evaluation_copies.hpp"

#include <algorithm>
#include <deque>
#include <set>

#include "apex/core/manifest.hpp"
#include "apex/core/message.hpp"

namespace apex_nodes {
namespace tuning {

namespace {

/** Every node `from` is fed by, directly or not, through any connection (not past `stop`), with
 *  how many hops upstream it is. */
std::map<std::string, int> upstreamOf(const apex::GraphDescription& g, const std::string& from, const std::string& stop) {
  std::map<std::string, int> seen{{from, 0}};
  std::deque<std::string> todo{from};
  while (!todo.empty()) {
    const std::string n = todo.front();
    todo.pop_front();
    for (const auto& c : g.connections)
      if (c.to_node == n && c.from_node != stop && seen.emplace(c.from_node, seen[n] + 1).second) todo.push_back(c.from_node);
  }
  return seen;
}

/** `from` and every node they feed, directly or not. */
std::set<std::string> downstreamOf(const apex::GraphDescription& g, const std::set<std::string>& from) {
  std::set<std::string> seen = from;
  std::deque<std::string> todo(from.begin(), from.end());
  while (!todo.empty()) {
    const std::string n = todo.front();
    todo.pop_front();
    for (const auto& c : g.connections)
      if (c.from_node == n && seen.insert(c.to_node).second) todo.push_back(c.to_node);
  }
  return seen;
}

}  // namespace

apex::Result<EvaluatedPart> evaluatedPart(const apex::GraphDescription& g, const std::string& name) {
  if (name.find('/') != std::string::npos)
    return apex::Status::error("an Optimizer inside a subgraph ('" + name +
                               "') evaluates in the graph only: move it to the top to use workers");
  EvaluatedPart part;
  for (const auto& c : g.connections)
    if (c.to_node == name && c.from_node != name) part.senders[c.to_port] = {c.from_node, c.from_port};
  if (!part.senders.count("fitness")) return apex::Status::error("nothing feeds the fitness: connect the score's mean to it");
  const std::map<std::string, int> hops = upstreamOf(g, part.senders.at("fitness").first, name);
  std::set<std::string> nodes;
  for (const auto& [input, sender] : part.senders)
    for (const auto& [node, n] : upstreamOf(g, sender.first, name)) nodes.insert(node);
  std::set<std::string> triggers;
  if (const auto* self = apex::findNode(g, name); self && self->interface)
    for (const auto& t : self->interface->triggers) triggers.insert(t.name);
  part.graph.thread_groups = g.thread_groups;
  for (const auto& n : g.nodes)
    if (nodes.count(n.name)) part.graph.nodes.push_back(n);
  for (const auto& c : g.connections) {
    if (!nodes.count(c.to_node)) continue;
    if (nodes.count(c.from_node)) part.graph.connections.push_back(c);
    else if (c.from_node == name && triggers.count(c.from_port)) part.slots[c.from_port].emplace_back(c.to_node, c.to_port);
    else if (c.from_node == name) part.targets[c.from_port].emplace_back(c.to_node, c.to_port);
  }
  // The nearest to the fitness first (the mean's reset before the player's restart): a frame of
  // the new pass cannot reach the mean before its reset does.
  for (auto& [trigger, slots] : part.slots)
    std::stable_sort(slots.begin(), slots.end(), [&](const auto& a, const auto& b) {
      const auto ha = hops.find(a.first), hb = hops.find(b.first);
      return (ha == hops.end() ? 1 << 30 : ha->second) < (hb == hops.end() ? 1 << 30 : hb->second);
    });
  if (!part.slots.count("evaluate"))
    return apex::Status::error(
        "its 'evaluate' reaches none of the nodes the fitness comes from: connect it to the "
        "player's restart and the mean's reset");
  return part;
}

apex::Result<std::unique_ptr<EvaluationCopies>> EvaluationCopies::make(const EvaluatedPart& part,
                                                                       const std::function<std::unique_ptr<apex::Graph>()>& make,
                                                                       int count, Scored scored) {
  std::unique_ptr<EvaluationCopies> out(new EvaluationCopies());
  out->part_ = part;
  for (const auto& [output, targets] : part.targets)
    for (const auto& [node, param] : targets) out->tuned_.insert(node);
  out->costly_ = downstreamOf(part.graph, out->tuned_);
  for (int i = 0; i < count; ++i) {
    auto g = make();
    g->setRerunOnEdit(false);  // each candidate's values are set by edits: no held frame into its pass
    auto loaded = g->load(part.graph);
    if (!loaded) return apex::Status::error("copy " + std::to_string(i + 1) + " of the evaluated part: " + loaded.message());
    for (const auto& [input, sender] : part.senders) {
      auto tap = [i, input = input, scored](const apex::Message& m) {
        if (auto v = m.as<double>()) scored(i, input, *v);
      };
      if (auto st = g->setTap(sender.first, sender.second, tap); !st)
        return apex::Status::error("copy " + std::to_string(i + 1) + " of the evaluated part: " + st.message());
    }
    out->copies_.push_back(std::move(g));
    out->started_.push_back(false);
    out->at_start_.emplace_back();
  }
  return out;
}

EvaluationCopies::~EvaluationCopies() {
  for (auto& g : copies_) g->stop();  // every tap is quiet before the next copy goes
}

apex::Status EvaluationCopies::evaluate(int i, const std::vector<std::pair<std::string, std::string>>& values) {
  apex::Graph& g = *copies_.at(i);
  at_start_.at(i) = workOf(i);  // the last pass is over: its score came
  for (const auto& [output, text] : values) {
    auto it = part_.targets.find(output);
    if (it == part_.targets.end()) continue;
    for (const auto& [node, param] : it->second)
      if (auto set = g.setParameter(node, param, text); !set) return set.status();
  }
  if (auto st = fire(i, "evaluate"); !st) return st;
  if (!started_[i]) g.start(), started_[i] = true;
  return apex::Status::ok();
}

apex::Status EvaluationCopies::fire(int i, const std::string& trigger) {
  auto it = part_.slots.find(trigger);
  if (it == part_.slots.end()) return apex::Status::ok();
  for (const auto& [node, slot] : it->second)
    if (auto st = copies_.at(i)->fireSlot(node, slot); !st) return st;
  return apex::Status::ok();
}

EvaluationCopies::Work EvaluationCopies::workOf(int i) const {
  Work w;
  for (apex::NodeStats& s : copies_.at(i)->nodeStats())
    if (costly_.count(s.name.substr(0, s.name.find('/'))))  // a subgraph's nodes count as it
      w[s.name] = std::move(s);
  return w;
}

double EvaluationCopies::msPerFrame(int i) const {
  const Work now = workOf(i), start = at_start_.at(i);
  const auto before = [&](const std::string& name) { return start.count(name) ? start.at(name) : apex::NodeStats(); };
  std::uint64_t frames = 0;  // of the pass: the most firings of a tuned node (each fires once a frame)
  for (const auto& [name, s] : now)
    if (tuned_.count(name.substr(0, name.find('/')))) frames = std::max(frames, s.firings - before(name).firings);
  if (frames == 0) return 0;
  double ns = 0;
  for (const auto& [name, s] : now) {
    const apex::NodeStats b = before(name);
    const std::uint64_t timed = s.timed_firings - b.timed_firings;
    // the mean over the pass's timed firings (a fast node times one in 8), else over its life
    const double mean = timed > 0 ? double(s.timed_ns - b.timed_ns) / double(timed) : double(s.mean_ns);
    ns += mean * double(s.firings - b.firings);
  }
  return ns / 1e6 / double(frames);
}

}  // namespace tuning
}  // namespace apex_nodes
