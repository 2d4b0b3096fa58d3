// The spec of live editing: a graph with two sources in two thread groups,
// joins fed by one source through paths of different length, parameter ports
// and events runs while a seeded random sequence of edits is applied. After each
// batch: every sink whose path is whole gets data within 1 s; once the graph is
// put back together, every sink does; no join ever pairs messages of two frames
// of one source; no removed node ever fires.
//   APEX_SOAK_EDITS (default 100000), APEX_SOAK_SEED (default: random, printed).
#include <gmock/gmock.h>

#include <cstdlib>
#include <random>
#include <set>
#include <sstream>

#include "apex_test/test_nodes.hpp"

namespace soak {
/** One frame of one source. */
struct Frame {
  int source;
  long n;
};
}  // namespace soak
APEX_TYPE_NAME(soak::Frame, "soak::Frame");

using namespace apex_test;
using soak::Frame;

namespace {

/** What the nodes saw, across node objects (a removed node's replacement is a new object). */
struct Board {
  std::mutex m;
  std::condition_variable arrived;
  std::map<std::string, long> received;  // sink name -> frames received (not Nothing)
  std::set<long> removed;  // ids of node objects that were removed
  long violations = 0;
  std::string first_violation;

  void violate(const std::string& what) {
    std::lock_guard<std::mutex> l(m);
    if (violations++ == 0) first_violation = what;
  }
  bool wasRemoved(long id) {
    std::lock_guard<std::mutex> l(m);
    return removed.count(id) > 0;
  }
  long count(const std::string& sink) {
    std::lock_guard<std::mutex> l(m);
    return received[sink];
  }
};
Board board;
std::atomic<long> next_id{0};

/** Every soak node checks that it does not fire after its removal. */
class SoakNode : public Node {
 public:
  const long id = next_id++;

 protected:
  void checkAlive() {
    if (board.wasRemoved(id)) board.violate("node '" + name() + "' fired after it was removed");
  }
};

/** A free-running source of frames; `gain` can be made interactive (a parameter output). */
class Source : public SoakNode {
 public:
  static Manifest manifest() {
    return Manifest("frames as fast as they are read")
        .output<Frame>("out")
        .output<int>("n")
        .param(param::integer("id", 1))
        .param(param::range("gain", 0, 100, 1, 1).makeInteractive());
  }
  void process() override {
    checkAlive();
    publish("out", Frame{param<int>("id"), n_});
    publish("n", static_cast<int>(n_ % 100));
    ++n_;
  }

 private:
  long n_ = 0;
};

/** A source at a rate, from its group's timer (a driven source). */
class Timed : public Source {
 public:
  static Manifest manifest() { return Source::manifest().driven(); }
  void setup() override { notifyNewData(); }
  void process() override {
    Source::process();
    notifyAfter(0.0002);
  }
};

/** Passes frames on; `offset` is interactive (fed by data or by another parameter). */
class Pass : public SoakNode {
 public:
  static Manifest manifest() {
    return Manifest("passes frames")
        .input<Frame>("in")
        .output<Frame>("out")
        .param(param::range("offset", 0, 100, 1, 0).makeInteractive())
        .slot("poke", &Pass::poke, "counts");
  }
  void process() override {
    checkAlive();
    publish("out", *input<Frame>("in"));
  }
  void poke() { ++pokes_; }

 private:
  long pokes_ = 0;
};

/** Two frames in (three with `extra`: an interface per instance), the first out: frames
 *  of one source must be the same frame. */
class Join : public SoakNode {
 public:
  static Manifest manifest() {
    return Manifest("checks a pair")
        .input<Frame>("a")
        .input<Frame>("b")
        .output<Frame>("out")
        .param(param::boolean("extra", false).shapesInterface())
        .shapedBy([](const ParamValues& p, Manifest& m) {
          if (p.get<bool>("extra")) m.optionalInput<Frame>("c");
          return Status::ok();
        });
  }
  void process() override {
    checkAlive();
    auto a = input<Frame>("a");
    check(*a, *input<Frame>("b"));
    if (interface().findInput("c") && hasInput("c")) check(*a, *input<Frame>("c"));
    publish("out", *a);
  }

 private:
  void check(const Frame& a, const Frame& b) {
    if (a.source != b.source || a.n == b.n) return;
    std::ostringstream s;
    s << "join '" << name() << "' paired frame " << a.n << " with frame " << b.n << " of source " << a.source;
    board.violate(s.str());
  }
};

class Sink : public SoakNode {
 public:
  static Manifest manifest() { return Manifest("counts frames").input<Frame>("in").slot("poke", &Sink::poke, "counts"); }
  void process() override {
    checkAlive();
    std::lock_guard<std::mutex> l(board.m);
    ++board.received[name()];
    board.arrived.notify_all();
  }
  void poke() {}
};

struct Spec {
  std::string name, type, group;
};
struct Link {
  std::string from, from_port, to, to_port;
};

// s1 -> p1 -> p2 -> p3 -> j1.a, s1 -> j1.b, j1 -> k1      (paths of 4 and 1 hops, groups a and b)
// j1 -> j3.a, p1 -> j3.b, j3 -> k3                        (a join of joins)
// s2 -> q1 -> j2.a, s2 -> q2 -> q3 -> j2.b, j2 -> k2       (the second source, in group b)
// s2.n -> p1.offset (data into a parameter), s1.gain -> p3.offset (parameter to parameter)
// s1.processed -> k1.poke, j2.processed -> p2.poke       (events)
const std::vector<Spec> kNodes = {{"s1", "soak/Source", "a"}, {"p1", "soak/Pass", "a"}, {"p2", "soak/Pass", "a"},
                                  {"p3", "soak/Pass", "b"},   {"j1", "soak/Join", "b"}, {"k1", "soak/Sink", "b"},
                                  {"j3", "soak/Join", "a"},   {"k3", "soak/Sink", "a"}, {"s2", "soak/Timed", "b"},
                                  {"q1", "soak/Pass", "b"},   {"q2", "soak/Pass", "a"}, {"q3", "soak/Pass", "b"},
                                  {"j2", "soak/Join", "b"},   {"k2", "soak/Sink", "b"}};
const std::vector<Link> kLinks = {
    {"s1", "out", "p1", "in"},        {"p1", "out", "p2", "in"},      {"p2", "out", "p3", "in"},
    {"p3", "out", "j1", "a"},         {"s1", "out", "j1", "b"},       {"j1", "out", "k1", "in"},
    {"j1", "out", "j3", "a"},         {"p1", "out", "j3", "b"},       {"j3", "out", "k3", "in"},
    {"s2", "out", "q1", "in"},        {"q1", "out", "j2", "a"},       {"s2", "out", "q2", "in"},
    {"q2", "out", "q3", "in"},        {"q3", "out", "j2", "b"},       {"j2", "out", "k2", "in"},
    {"s2", "n", "p1", "offset"},      {"s1", "gain", "p3", "offset"}, {"s1", "processed", "k1", "poke"},
    {"j2", "processed", "p2", "poke"}};
// The data links each sink needs (its upstream), for "the rest keeps running".
const std::map<std::string, std::vector<int>> kSinkPaths = {
    {"k1", {0, 1, 2, 3, 4, 5}}, {"k3", {0, 1, 2, 3, 4, 6, 7, 8}}, {"k2", {9, 10, 11, 12, 13, 14}}};
// Connections a careless user might make: another source into a join, a cycle.
// p2 -> j1.c and q2 -> j2.c exist only while the join has `extra` (its interface changes).
const std::vector<Link> kStray = {{"s2", "out", "j1", "a"},  {"q3", "out", "p1", "in"}, {"j1", "out", "p1", "in"},
                                  {"s1", "out", "q2", "in"}, {"j3", "out", "q1", "in"}, {"p2", "out", "j1", "c"},
                                  {"q2", "out", "j2", "c"}};
const std::vector<std::string> kGroups = {"default", "a", "b", "c"};

NodeRegistry soakRegistry() {
  NodeRegistry r;
  EXPECT_TRUE(r.add<Source>("soak/Source"));
  EXPECT_TRUE(r.add<Timed>("soak/Timed"));
  EXPECT_TRUE(r.add<Pass>("soak/Pass"));
  EXPECT_TRUE(r.add<Join>("soak/Join"));
  EXPECT_TRUE(r.add<Sink>("soak/Sink"));
  return r;
}

long envOr(const char* name, long fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::atol(v) : fallback;
}

// With subgraphs: these nodes are grouped into A and B (inner names A/p1, ...), and random
// edits also ungroup and group them again while the data flows.
const std::map<std::string, std::vector<std::string>> kSubgraphs = {{"A", {"p1", "p2", "p3"}}, {"B", {"q2", "q3", "j2"}}};

std::string base(const std::string& path) { return path.substr(path.rfind('/') + 1); }

class Soak {
 public:
  Soak(std::uint64_t seed, bool subgraphs) : rng_(seed), g_(soakRegistry()), subgraphs_(subgraphs) {}

  void build() {
    for (const auto& n : kNodes) addNode(n);
    restore();
  }

  /** Where a node of the design is now: "A/p1" while A is grouped, else "p1". */
  std::string path(const std::string& node) const {
    for (const auto& [sub, members] : kSubgraphs)
      if (grouped_.count(sub) && std::find(members.begin(), members.end(), node) != members.end()) return sub + "/" + node;
    return node;
  }

  /** One random edit; refused edits are fine (they must change nothing). */
  void randomEdit() {
    const std::string name = kNodes[pick(kNodes.size())].name;
    const std::string node = path(name);
    switch (pick(subgraphs_ ? 14 : 13)) {
      case 0:
      case 1: {
        const Link& l = kLinks[pick(kLinks.size())];
        (void)g_.disconnect(path(l.from), l.from_port, path(l.to), l.to_port);
        break;
      }
      case 2:
      case 3: {
        const Link& l = kLinks[pick(kLinks.size())];
        (void)g_.connect(path(l.from), l.from_port, path(l.to), l.to_port);
        break;
      }
      case 4:
        remove(node);
        break;
      case 5:
        if (!exists(node)) addNode(spec(name));
        break;
      case 6:
        if (pick(3) != 0) {
          (void)g_.setThreadGroup(node, kGroups[pick(kGroups.size())]);
        } else if (g_.rename(node, name + "_renamed")) {  // and back: the design's names stay
          const std::string renamed = node.substr(0, node.size() - name.size()) + name + "_renamed";
          EXPECT_TRUE(g_.rename(renamed, name)) << renamed;
        }
        break;
      case 7:
        (void)g_.setEnabled(node, pick(3) != 0);
        break;
      case 8: {
        (void)g_.setParameter(node, paramOf(node), std::to_string(pick(100)));
        if (pick(4) == 0) (void)g_.setInteractive(node, paramOf(node), pick(2) == 0);
        break;
      }
      case 9:
        (void)g_.fireSlot(node, pick(2) ? "poke" : "enable");
        break;
      case 10: {
        const Link& l = kStray[pick(kStray.size())];
        (void)g_.connect(path(l.from), l.from_port, path(l.to), l.to_port);
        break;
      }
      case 12:
        if (name[0] == 'j') (void)g_.setParameter(node, "extra", pick(2) ? "true" : "false");
        break;
      case 13:
        toggleSubgraph(std::next(kSubgraphs.begin(), static_cast<long>(pick(kSubgraphs.size())))->first);
        break;
      case 11:
        if (!g_.paused()) {
          if (pick(4) == 0) g_.pause();
        } else if (pick(2)) {
          g_.step();
        } else {
          g_.resume();
        }
        break;
    }
  }

  /** Sinks whose whole upstream is there, enabled and connected as designed. A disabled
   *  source joined to a sink's part by a stray link holds it like a silent sensor (a join
   *  waits for every live input): such a sink is not checked. */
  std::vector<std::string> wholeSinks() {
    const std::vector<ConnectionDescription> connections = g_.connections();  // by the nodes' paths
    std::set<std::string> enabled;
    for (const auto& n : g_.nodeStats())
      if (n.enabled) enabled.insert(n.name);
    auto has = [&](const Link& l) {
      for (const auto& c : connections)
        if (c.from_node == path(l.from) && c.from_port == l.from_port && c.to_node == path(l.to) && c.to_port == l.to_port)
          return true;
      return false;
    };
    std::vector<std::string> out;
    for (const auto& [sink, links] : kSinkPaths) {
      bool whole = enabled.count(path(sink)) > 0;
      for (int i : links)
        whole = whole && has(kLinks[i]) && enabled.count(path(kLinks[i].from)) && enabled.count(path(kLinks[i].to));
      for (const auto& source : dataPart(connections, path(sink)))
        whole = whole && (base(source)[0] != 's' || enabled.count(source));
      if (whole) out.push_back(sink);
    }
    return out;
  }

  /** The nodes joined to `node` by data connections (not events, not into parameters). */
  static std::set<std::string> dataPart(const std::vector<ConnectionDescription>& connections, const std::string& node) {
    std::set<std::string> part{node};
    for (bool grew = true; grew;) {
      grew = false;
      for (const auto& c : connections) {
        if (c.from_port == "processed" || (!paramOf(c.to_node).empty() && c.to_port == paramOf(c.to_node))) continue;
        if (part.count(c.from_node) != part.count(c.to_node))
          grew = part.insert(c.from_node).second | part.insert(c.to_node).second;
      }
    }
    return part;
  }

  /** Puts the designed graph back: every node, enabled, interactive, every link, no stray one; running. */
  void restore() {
    for (const auto& n : kNodes) {
      if (!exists(path(n.name))) addNode(n);
      ASSERT_TRUE(g_.setEnabled(path(n.name), true));
      if (!paramOf(n.name).empty()) {
        ASSERT_TRUE(g_.setInteractive(path(n.name), paramOf(n.name), true));
      }
    }
    if (subgraphs_)
      for (const auto& [sub, members] : kSubgraphs)
        if (!grouped_.count(sub)) toggleSubgraph(sub);
    for (const auto& l : kStray) (void)g_.disconnect(path(l.from), l.from_port, path(l.to), l.to_port);
    for (const auto& l : kLinks) {
      auto st = g_.connect(path(l.from), l.from_port, path(l.to), l.to_port);
      ASSERT_TRUE(st || st.message().find("already connected") != std::string::npos) << st.message();
    }
    if (g_.paused()) g_.resume();
  }

  /** Every sink in `sinks` receives at least two more frames within `seconds`. */
  std::string flowing(const std::vector<std::string>& sinks, double seconds) {
    std::unique_lock<std::mutex> l(board.m);
    std::map<std::string, long> start;
    for (const auto& s : sinks) start[s] = board.received[s];
    auto late = [&] {
      std::string out;
      for (const auto& s : sinks)
        if (board.received[s] < start[s] + 2) out += (out.empty() ? "" : ", ") + s;
      return out;
    };
    if (board.arrived.wait_for(l, std::chrono::duration<double>(seconds), [&] { return late().empty(); })) return "";
    return late() + " got no data within " + std::to_string(seconds) + " s";
  }

  Graph& graph() { return g_; }

  /** What every node is doing, for a failure message. */
  std::string dump() {
    std::ostringstream s;
    for (const auto& n : g_.nodeStats(0))
      s << "\n  " << n.name << ": " << n.firings << " firings, idle " << n.idle_s << " s" << (n.enabled ? "" : ", disabled")
        << (n.waiting_for.empty() ? "" : ", " + n.waiting_for);
    return s.str();
  }

 private:
  std::size_t pick(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); }
  bool exists(const std::string& n) { return g_.nodeObject(n) != nullptr; }
  /** The interactive parameter of a node, "" if none. */
  static std::string paramOf(const std::string& path) {
    const char kind = base(path)[0];
    if (kind == 's') return "gain";
    return kind == 'p' || kind == 'q' ? "offset" : "";
  }
  /** Groups a set of the design's nodes (those there now) into its subgraph, or ungroups it. */
  void toggleSubgraph(const std::string& sub) {
    if (grouped_.count(sub)) {
      ASSERT_TRUE(g_.ungroup(sub));
      grouped_.erase(sub);
      return;
    }
    std::vector<std::string> present;
    for (const auto& m : kSubgraphs.at(sub))
      if (exists(m)) present.push_back(m);
    if (present.size() != kSubgraphs.at(sub).size()) return;  // grouped whole, so that paths stay simple
    auto st = g_.group(present, sub);
    ASSERT_TRUE(st) << st.message();
    grouped_.insert(sub);
  }
  static const Spec& spec(const std::string& name) {
    for (const auto& n : kNodes)
      if (n.name == name) return n;
    throw std::logic_error("no spec " + name);
  }
  void addNode(const Spec& n) {
    auto r = g_.addNode(n.type, path(n.name), n.group);
    ASSERT_TRUE(r) << r.message();
    if (n.name == "s2") {
      ASSERT_TRUE(g_.setParameter("s2", "id", "2"));
    }
  }
  void remove(const std::string& n) {
    auto* object = dynamic_cast<SoakNode*>(g_.nodeObject(n));
    if (!object) return;
    const long id = object->id;
    ASSERT_TRUE(g_.removeNode(n));
    std::lock_guard<std::mutex> l(board.m);
    board.removed.insert(id);  // from here on it must never fire
  }

  std::mt19937_64 rng_;
  Graph g_;
  const bool subgraphs_;
  std::set<std::string> grouped_;  // subgraphs of kSubgraphs that are there now
};

void soakTest(bool subgraphs) {
  const long edits = envOr("APEX_SOAK_EDITS", 100000) / (subgraphs ? 2 : 1);
  const std::uint64_t seed =
      static_cast<std::uint64_t>(envOr("APEX_SOAK_SEED", static_cast<long>(std::random_device{}() & 0x7fffffff)));
  SCOPED_TRACE("replay with APEX_SOAK_SEED=" + std::to_string(seed) + " APEX_SOAK_EDITS=" + std::to_string(edits));
  std::printf("soak: %ld edits, seed %llu\n", edits, static_cast<unsigned long long>(seed));
  Soak soak(seed, subgraphs);
  soak.build();
  soak.graph().start();
  ASSERT_EQ(soak.flowing({"k1", "k2", "k3"}, 5.0), "");

  std::mt19937_64 batch_rng(seed ^ 0x5eed);
  long done = 0, batches = 0;
  while (done < edits) {
    const long batch = 1 + static_cast<long>(batch_rng() % 60);
    for (long i = 0; i < batch && done < edits; ++i, ++done) soak.randomEdit();
    ++batches;
    // The rest keeps running: sinks whose path is whole get data while others are cut off.
    if (!soak.graph().paused()) {
      const auto whole = soak.wholeSinks();
      ASSERT_EQ(soak.flowing(whole, 1.0), "")
          << "after " << done << " edits (batch " << batches << "), the graph cut elsewhere" << soak.dump();
    }
    soak.restore();
    ASSERT_EQ(soak.flowing({"k1", "k2", "k3"}, 1.0), "")
        << "after " << done << " edits (batch " << batches << "), put back" << soak.dump();
    std::lock_guard<std::mutex> l(board.m);
    ASSERT_EQ(board.violations, 0) << board.first_violation << " (after " << done << " edits)";
  }
  soak.graph().stop();
  std::printf("soak: %ld batches; frames at the sinks: k1 %ld, k2 %ld, k3 %ld\n", batches, board.count("k1"), board.count("k2"),
              board.count("k3"));
}

TEST(Soak, RandomEditsWhileDataFlowsNeverStallOrMixFrames) { soakTest(false); }

// The same inside subgraphs, with grouping and ungrouping among the edits.
TEST(Soak, RandomEditsInsideSubgraphsAndGroupingWhileDataFlowsNeverStallOrMixFrames) { soakTest(true); }

}  // namespace
