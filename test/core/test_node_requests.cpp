// What node code may ask of its graph besides edits: to run a function later on its own thread
// group, called from any thread (Node::runLater), and the graph's description with a maker of
// graphs like it (Node::describeGraph), as the Optimizer's workers use them.
#include <gmock/gmock.h>

#include <thread>

#include "apex_test/test_nodes.hpp"

using namespace apex_test;

namespace {

/** `spawn`: a thread of its own sends 7 through runLater. `copy`: describes the graph, makes a
 *  graph like it holding a copy of node `relay`, and sends how many nodes each one has. */
class Asker : public Node {
 public:
  static Manifest manifest() {
    return Manifest("asks its graph")
        .output<int>("out")
        .trigger("done")
        .slot("spawn", &Asker::spawn)
        .slot("copy", &Asker::copy)
        .driven();  // a source that fires only when asked: nothing of its own on `out`
  }
  ~Asker() override {
    if (worker_.joinable()) worker_.join();
  }
  void process() override {}
  void spawn() {
    worker_ = std::thread([this] { runLater([this] { publish("out", 7), trigger("done"); }); });
  }
  void copy() {
    describeGraph([this](const GraphSnapshot& snapshot) {
      GraphDescription part;
      for (const auto& n : snapshot.description.nodes)
        if (n.name == "relay") part.nodes.push_back(n);
      copy_ = snapshot.makeGraph();
      auto loaded = copy_->load(part);
      if (!loaded) throw std::runtime_error(loaded.message());
      publish("out", static_cast<int>(snapshot.description.nodes.size() * 10 + copy_->size()));
    });
  }
  std::unique_ptr<Graph> copy_;

 private:
  std::thread worker_;
};

NodeRegistry registry() {
  NodeRegistry r = testRegistry();
  EXPECT_TRUE(r.add<Asker>("test/Asker"));
  return r;
}

std::vector<int> ints(Collector* c) {
  std::vector<int> out;
  for (const auto& m : c->messages())
    if (auto v = m.as<int>()) out.push_back(*v);
  return out;
}

TEST(NodeRequests, AFunctionRunLaterFromAnotherThreadRunsAsASlotHandlerDoes) {
  Graph g(registry());
  add(g, "test/Asker", "asker");
  add(g, "test/Collector", "sink");
  add(g, "test/Sequence", "seq");
  add(g, "test/Collector", "played");
  link(g, "asker", "out", "sink", "in");
  link(g, "asker", "done", "seq", "restart");
  link(g, "seq", "out", "played", "in");
  g.start();
  ASSERT_TRUE(g.fireSlot("asker", "spawn"));
  ASSERT_TRUE(waitUntil([&] { return !ints(object<Collector>(g, "sink")).empty(); }));
  EXPECT_EQ(ints(object<Collector>(g, "sink")), std::vector<int>{7}) << "what it published went out";
  EXPECT_TRUE(waitUntil([&] { return ints(object<Collector>(g, "played")).size() == 3; })) << "and its event after it";
}

TEST(NodeRequests, ANodeGetsItsGraphsDescriptionAndMakesAGraphLikeIt) {
  Graph g(registry());
  add(g, "test/Asker", "asker");
  add(g, "test/Relay", "relay");
  add(g, "test/Collector", "sink");
  link(g, "asker", "out", "sink", "in");
  g.start();
  ASSERT_TRUE(g.fireSlot("asker", "copy"));
  ASSERT_TRUE(waitUntil([&] { return !ints(object<Collector>(g, "sink")).empty(); }));
  EXPECT_EQ(ints(object<Collector>(g, "sink")), std::vector<int>{31}) << "three nodes here, one in the copy";
  EXPECT_EQ(object<Asker>(g, "asker")->copy_->registry().ids(), g.registry().ids()) << "the graph's own node types";
  EXPECT_EQ(g.size(), 3u);
}

}  // namespace
