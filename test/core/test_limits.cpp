// One set of limits for edits and files (apex/core/limits.hpp): what an edit builds can always
// be saved and loaded back, and an edit past a limit is refused with a message naming it.
#include <gmock/gmock.h>

#include "apex/core/graph_file.hpp"
#include "apex/core/limits.hpp"
#include "apex_test/graph_file_helpers.hpp"
#include "apex_test/test_nodes.hpp"

using namespace apex_test;
using ::testing::HasSubstr;

namespace {

class Labelled : public Node {  // a node with a text parameter
 public:
  static Manifest manifest() { return Manifest("holds a label").param(param::text("label", "")); }
  void process() override {}
};

NodeRegistry registry() {
  NodeRegistry r = testRegistry();
  EXPECT_TRUE(r.add<Labelled>("test/Labelled"));
  return r;
}

/** The graph saved to a file and loaded into a new graph: what the second one describes. */
Result<GraphDescription> roundTrip(const Graph& g, const TempDir& dir) {
  const std::string path = dir.file("limits.yaml");
  if (auto st = saveGraphFile(g, path); !st) return st;
  Graph again(registry());
  auto loaded = loadGraphFile(again, path);
  if (!loaded) return loaded.status();
  return again.describe();
}

TEST(Limits, ThreadGroupsStopAtTheLimitAndSuchAGraphLoadsBack) {
  TempDir dir;
  Graph g(registry());
  for (std::size_t i = 1; i < kMaxGraphGroups; ++i)  // with "default": the limit
    ASSERT_TRUE(g.addNode("test/Relay", "r" + std::to_string(i), "g" + std::to_string(i)));
  auto over = g.addNode("test/Relay", "one_more", "g_new");
  ASSERT_FALSE(over);
  EXPECT_EQ(over.message(),
            "cannot add node 'one_more': thread group 'g_new': the graph has 256 thread groups, the "
            "limit (each is a thread of the process)");
  EXPECT_TRUE(g.addNode("test/Relay", "in_an_old_group", "g7")) << "groups that exist take more nodes";
  EXPECT_THAT(g.setThreadGroup("r1", "g_new").message(), HasSubstr("256 thread groups, the limit"));
  auto back = roundTrip(g, dir);
  ASSERT_TRUE(back) << back.message();
  EXPECT_EQ(back.value().thread_groups.size() + 1, kMaxGraphGroups);  // and "default", which a file never lists

  GraphDescription unknown;  // nodes of a type not installed here keep their group, and count too
  for (std::size_t i = 0; i < kMaxGraphGroups; ++i) {
    NodeDescription n;
    n.name = "old" + std::to_string(i), n.type = "retired/Thing", n.thread_group = "t" + std::to_string(i);
    unknown.nodes.push_back(n);
  }
  Graph other(registry());
  EXPECT_THAT(other.load(unknown).message(), HasSubstr("node 'old255': thread group 't255': the graph has 256 thread groups"));
}

TEST(Limits, NodesStopAtTheLimitAndSuchAGraphLoadsBack) {
  TempDir dir;
  Graph g(registry());
  for (std::size_t i = 0; i < kMaxGraphNodes; ++i) ASSERT_TRUE(g.addNode("test/Relay", "r" + std::to_string(i)));
  EXPECT_EQ(g.addNode("test/Relay", "one_more").message(),
            "cannot add node 'one_more': the graph has 20000 nodes; 1 more would pass the limit of 20000");
  auto back = roundTrip(g, dir);
  ASSERT_TRUE(back) << back.message();
  EXPECT_EQ(back.value().nodes.size(), kMaxGraphNodes);
}

TEST(Limits, ConnectionsStopAtTheLimitAndSuchAGraphLoadsBack) {
  TempDir dir;
  GraphDescription d;  // 1000 nodes, each one's processed -> the next 100's enable: 100,000 event links
  const std::size_t nodes = 1000, fan_out = kMaxGraphConnections / nodes;
  for (std::size_t i = 0; i < nodes; ++i) {
    NodeDescription n;
    n.name = "r" + std::to_string(i), n.type = "test/Relay";
    d.nodes.push_back(n);
  }
  for (std::size_t i = 0; i < nodes; ++i)
    for (std::size_t k = 1; k <= fan_out; ++k)
      d.connections.push_back({"r" + std::to_string(i), "processed", "r" + std::to_string((i + k) % nodes), "enable", 0});
  Graph g(registry());
  ASSERT_TRUE(g.load(d));
  auto over = g.connect("r0", "out", "r1", "in");
  ASSERT_FALSE(over);
  EXPECT_EQ(over.message(), "cannot connect r0/out -> r1/in: the graph has 100000 connections, the limit");
  ASSERT_TRUE(g.removeNode("r5"));  // takes 200 of them: room again
  EXPECT_TRUE(g.connect("r0", "out", "r1", "in"));
  auto back = roundTrip(g, dir);
  ASSERT_TRUE(back) << back.message();
  EXPECT_EQ(back.value().connections.size(), kMaxGraphConnections - 2 * fan_out + 1);
  d.connections.push_back({"r0", "out", "r1", "in", 0});  // one more than a graph may hold: refused whole
  Graph other(registry());
  EXPECT_THAT(other.load(d).message(), HasSubstr("the graph has 100000 connections, the limit"));
}

TEST(Limits, NamesValuesAndUiTextStayWithinWhatAFileHolds) {
  TempDir dir;
  Graph g(registry());
  const std::string longest(kMaxNameLength, 'n');
  ASSERT_TRUE(g.addNode("test/Labelled", longest));
  EXPECT_THAT(g.addNode("test/Labelled", longest + "n").message(), HasSubstr("at most 200 of them"));
  EXPECT_THAT(g.addNode("test/Labelled", "x", std::string(kMaxNameLength + 1, 'g')).message(), HasSubstr("thread group name"));

  ASSERT_TRUE(g.setParameter(longest, "label", std::string(kMaxYamlString, 'v')));
  EXPECT_EQ(g.setParameter(longest, "label", std::string(kMaxYamlString + 1, 'v')).message(),
            "node '" + longest + "': parameter 'label': a value of 65537 characters, over the limit of 65536");

  EXPECT_THAT(g.setUi(longest, "{x: .nan, y: 2}").message(), HasSubstr("holds '.nan', a number that is not finite"));
  EXPECT_THAT(g.setUi(longest, "{x: 1e309}").message(), HasSubstr("holds '1e309', a number that is not finite"));
  EXPECT_THAT(g.setUi(longest, "{pos: [1, -.inf]}").message(), HasSubstr("not finite"));
  std::string deep = "1";
  for (int i = 0; i <= kMaxYamlDepth; ++i) deep = "[" + deep + "]";
  EXPECT_THAT(g.setUi(longest, "{a: " + deep + "}").message(), HasSubstr("nested deeper than 32 levels"));
  EXPECT_THAT(g.setUi(longest, "{note: '" + std::string(kMaxYamlString, 'u') + "'}").message(),
              HasSubstr("over the limit of 65536"));
  EXPECT_THAT(g.setUi(longest, "{note: '.nan'}").message(), HasSubstr("not finite")) << "a file writes it back plain";
  EXPECT_TRUE(g.setUi(longest, "{x: 12.5, y: -3, note: 'nan bread 1e9'}"));
  auto back = roundTrip(g, dir);
  ASSERT_TRUE(back) << back.message();
  EXPECT_EQ(back.value().nodes.at(0).name, longest);
}

}  // namespace
