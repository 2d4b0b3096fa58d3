// Edits a node asks for itself (Node::requestEdit): a plugin host learns in setup() what its
// plugin offers and makes those parameters its own, through its interface function.
#include <gmock/gmock.h>

#include <atomic>
#include <chrono>
#include <mutex>

#include "../../apex_runtime/src/core/edit_requests.hpp"
#include "apex_test/test_nodes.hpp"

using namespace apex_test;

namespace {

using Texts = std::vector<std::string>;

/** Stands for a plugin host: its interface has an int parameter per name in `offered`, which it
 *  fills with what `plugin` offers (a comma list) in setup() and when `plugin` changes. */
class Host : public Node {
 public:
  static Manifest manifest() {
    return Manifest("offers its plugin's parameters")
        .param(param::text("plugin", "alpha,beta"))
        .param(param::textList("offered", {}).shapesInterface())
        .shapedBy([](const ParamValues& p, Manifest& m) {
          for (const auto& name : p.get<Texts>("offered")) {
            if (name.empty() || name.find(' ') != std::string::npos) return Status::error("'" + name + "' is no name");
            m.param(param::range(name, 0, 100, 1, 7));
          }
          return Status::ok();
        });
  }
  void setup() override {
    std::lock_guard<std::mutex> lock(m_);
    saw_ = param<std::string>("plugin") + " " + std::to_string(interface().params.size());
    requestEdit("offered", offers());
  }
  void process() override {}
  /** What setup() saw: the plugin and how many parameters the node had ("" before setup). */
  std::string setupSaw() const {
    std::lock_guard<std::mutex> lock(m_);
    return saw_;
  }
  void parameterChanged(const std::string& name) override {
    if (name == "plugin") requestEdit("offered", offers());
  }

 private:
  mutable std::mutex m_;
  std::string saw_;

  Texts offers() const {
    Texts out;
    const std::string& s = param<std::string>("plugin");
    for (std::size_t at = 0; at <= s.size();) {
      const auto comma = std::min(s.find(',', at), s.size());
      out.push_back(s.substr(at, comma - at));
      at = comma + 1;
    }
    return out;
  }
};

/** A source that keeps asking, each firing. */
class Asker : public Host {
 public:
  static Manifest manifest() { return Host::manifest().output<int>("out"); }
  void process() override {
    requestEdit("offered", Texts{"gamma"});
    publish("out", 1);
  }
};

NodeRegistry registry() {
  NodeRegistry r = testRegistry();
  EXPECT_TRUE(r.add<Host>("test/Host"));
  EXPECT_TRUE(r.add<Asker>("test/Asker"));
  return r;
}

bool hasParam(const Graph& g, const std::string& node, const std::string& param) {
  auto iface = g.nodeInterface(node);
  return iface && iface->findParam(param);
}

std::string errorOf(const Graph& g, const std::string& node) {
  for (const auto& s : g.nodeStats(60))
    if (s.name == node) return s.error;
  return "(no node " + node + ")";
}

TEST(EditRequests, ANodeMakesWhatItsPluginOffersItsOwnParametersAfterSetup) {
  Graph g(registry());
  g.start();
  add(g, "test/Host", "host");
  ASSERT_TRUE(waitUntil([&] { return hasParam(g, "host", "alpha") && hasParam(g, "host", "beta"); }));
  EXPECT_EQ(g.parameterValue("host", "alpha").value(), ParamValue(7));
  // they are parameters like any other: set by edits, seen by the node, saved with the graph
  ASSERT_TRUE(g.setParameter("host", "beta", "42"));
  ASSERT_TRUE(waitUntil([&] { return g.parameterValue("host", "beta").value() == ParamValue(42); }));
  EXPECT_EQ(errorOf(g, "host"), "");
  // another plugin: the node asks again after the change and the interface follows
  ASSERT_TRUE(g.setParameter("host", "plugin", "gamma"));
  ASSERT_TRUE(waitUntil([&] { return hasParam(g, "host", "gamma") && !hasParam(g, "host", "alpha"); }));
  EXPECT_EQ(errorOf(g, "host"), "");
}

TEST(EditRequests, SetupSeesTheParametersANodeIsAddedWithAndTheParametersTheyShape) {
  // What a plugin host needs: setup() loads the plugin named by the parameters given with the
  // node (add_node's, a file's), never its defaults first; a parameter that the offered list
  // makes (`x`) can be given in the same description, after it.
  Graph g(registry());
  add(g, "test/Ticker", "busy");  // keeps the default group's thread at work: setup mail runs at once
  add(g, "test/Collector", "sink");
  link(g, "busy", "out", "sink", "in");
  g.start();
  for (int i = 0; i < 30; ++i) {
    NodeDescription d;
    d.name = "host_" + std::to_string(i);
    d.type = "test/Host";
    d.parameters = {{"plugin", "\"x,y\""}, {"offered", "[x, y]"}, {"x", "3"}};
    ASSERT_TRUE(g.addNode(d));
    ASSERT_TRUE(waitUntil([&] { return !object<Host>(g, d.name)->setupSaw().empty(); }));
    EXPECT_EQ(object<Host>(g, d.name)->setupSaw(), "x,y 4");  // plugin, offered, x, y
    EXPECT_EQ(g.parameterValue(d.name, "x").value(), ParamValue(3));
  }
}

TEST(EditRequests, AValueTheInterfaceRefusesIsTheNodesErrorNamingTheParameter) {
  Graph g(registry());
  g.start();
  NodeDescription d;
  d.name = "host";
  d.type = "test/Host";
  d.parameters = {{"plugin", "\"ok,not a name\""}};
  ASSERT_TRUE(g.addNode(d));
  ASSERT_TRUE(waitUntil([&] { return !errorOf(g, "host").empty(); }));
  EXPECT_THAT(errorOf(g, "host"), testing::HasSubstr("asked to set 'offered'"));
  EXPECT_THAT(errorOf(g, "host"), testing::HasSubstr("'not a name' is no name"));
  EXPECT_FALSE(hasParam(g, "host", "ok"));  // all or nothing
}

TEST(EditRequests, ARequestOfARemovedNodeIsDroppedAndNeverReachesANewNodeOfItsName) {
  Graph g(registry());
  g.start();
  for (int i = 0; i < 100; ++i) {
    add(g, "test/Host", "n");
    ASSERT_TRUE(g.removeNode("n"));
    add(g, "test/Relay", "n");  // no parameter 'offered': a request that reached it would be its error
    ASSERT_TRUE(g.removeNode("n"));
  }
  add(g, "test/Relay", "n");
  add(g, "test/Host", "last");
  ASSERT_TRUE(waitUntil([&] { return hasParam(g, "last", "alpha"); }));  // requests are applied in order
  EXPECT_EQ(errorOf(g, "n"), "");
}

TEST(EditRequests, AGraphGoesWhileItsNodesKeepAsking) {
  for (int i = 0; i < 20; ++i) {
    Graph g(registry());
    add(g, "test/Asker", "asker");
    add(g, "test/Collector", "sink");
    link(g, "asker", "out", "sink", "in");
    g.start();
    ASSERT_TRUE(waitUntil([&] { return hasParam(g, "asker", "gamma"); }));
  }  // each graph stops its requests first, then its nodes
}

TEST(EditRequests, ATimedTaskRunsWhenDueThoughItCameWhileTheThreadWaitedForNothing) {
  // (how an edit has holding sources told of it, off the edit: Graph::Impl::changedDownstreamOf)
  detail::EditRequests requests([](const std::shared_ptr<detail::NodeState>&, const std::string&, const ParamValue&) {},
                                [] { return GraphSnapshot{}; });
  std::atomic<int> ran{0};
  const auto now = [] { return std::chrono::steady_clock::now(); };
  ASSERT_TRUE(requests.runAt(now(), [&] { ran += 1; }));
  ASSERT_TRUE(waitUntil([&] { return ran == 1; }));  // its thread now waits with nothing to do
  const auto due = now() + std::chrono::milliseconds(50);
  ASSERT_TRUE(requests.runAt(due, [&] { ran += 10; }));
  EXPECT_FALSE(requests.runAt(now(), [&] { ran += 100; })) << "one waits already: it does the work of both";
  ASSERT_TRUE(waitUntil([&] { return ran == 11; }));
  EXPECT_GE(now(), due);
  requests.stop();
  EXPECT_FALSE(requests.runAt(now(), [&] { ran += 1000; }));
}

}  // namespace
