// Connection rules: each refusal names the problem, and a refused edit
// changes nothing.
#include <gmock/gmock.h>

#include "apex/core/graph_file.hpp"
#include "apex_test/test_nodes.hpp"

using namespace apex_test;
using ::testing::HasSubstr;

namespace {

struct Connect : ::testing::Test {
  Graph g{testRegistry()};
  void SetUp() override {
    add(g, "test/Feeder", "src");
    add(g, "test/Gain", "gain");
    add(g, "test/Gain", "gain2");
    add(g, "test/Counter", "counter");
    add(g, "test/Collector", "sink");
    add(g, "test/Feeder", "src2");
  }
  std::string text() const { return formatGraphText(g.describe()); }
  /** The edit is refused with a message holding `what`, and the graph is unchanged. */
  void refused(const Status& st, const std::string& before, const std::string& what) {
    ASSERT_FALSE(st);
    EXPECT_THAT(st.message(), HasSubstr(what));
    EXPECT_EQ(text(), before);
  }
};

TEST_F(Connect, UnknownNodeOrPortListsThePorts) {
  const auto before = text();
  refused(g.connect("nobody", "out", "gain", "in"), before, "no node named 'nobody'");
  auto st = g.connect("src", "outt", "gain", "in");
  refused(st, before, "has no output, trigger or parameter 'outt'");
  EXPECT_THAT(st.message(), HasSubstr("outputs: out"));
  st = g.connect("src", "out", "gain", "inn");
  refused(st, before, "has no input, slot or parameter 'inn'");
  EXPECT_THAT(st.message(), HasSubstr("inputs: in"));
}

TEST_F(Connect, WrongDirectionIsExplained) {
  const auto before = text();
  refused(g.connect("gain", "in", "sink", "in"), before, "'in' is an input of node 'gain'");
  refused(g.connect("src", "out", "gain", "out"), before, "'out' is an output of node 'gain'");
}

TEST_F(Connect, IncompatibleTypesNameBoth) {
  struct Strings : Node {
    static Manifest manifest() { return Manifest().output<std::string>("out"); }
    void process() override {}
  };
  ASSERT_TRUE(g.registry().add<Strings>("test/Strings"));
  add(g, "test/Strings", "words");
  const auto before = text();
  auto st = g.connect("words", "out", "gain", "in");
  refused(st, before, "type mismatch");
  EXPECT_THAT(st.message(), HasSubstr("carries string"));
  EXPECT_THAT(st.message(), HasSubstr("takes int"));
  EXPECT_TRUE(g.connect("words", "out", "sink", "in"));  // an Any input takes anything
}

TEST_F(Connect, AnInputHasOneSource) {
  link(g, "src", "out", "gain", "in");
  const auto before = text();
  refused(g.connect("src2", "out", "gain", "in"), before, "already connected (from src)");
}

TEST_F(Connect, OneOutputFeedsManyInputs) {
  link(g, "src", "out", "gain", "in");
  link(g, "src", "out", "gain2", "in");
  link(g, "src", "out", "sink", "in");
  EXPECT_EQ(g.describe().connections.size(), 3u);
}

TEST_F(Connect, RefusesCycles) {
  link(g, "src", "out", "gain", "in");
  link(g, "gain", "out", "gain2", "in");
  add(g, "test/OptionalSum", "sum");
  link(g, "gain2", "out", "sum", "a");
  const auto before = text();
  refused(g.connect("sum", "sum", "gain", "in"), before, "already connected");
  refused(g.connect("sum", "sum", "sum", "b"), before, "would close a cycle");
}

TEST_F(Connect, TriggersOnlyToSlots) {
  const auto before = text();
  refused(g.connect("counter", "every_n", "gain", "in"), before, "a trigger connects only to slots");
  refused(g.connect("src", "out", "counter", "reset"), before, "a slot receives only triggers");
  EXPECT_TRUE(g.connect("counter", "every_n", "counter", "reset"));  // events may loop
  EXPECT_TRUE(g.connect("counter", "processed", "gain", "disable"));
  refused(g.connect("counter", "every_n", "counter", "reset"), text(), "already connected");
}

TEST_F(Connect, ParameterPortsOnlyWhenInteractive) {
  const auto before = text();
  refused(g.connect("gain", "gain", "gain2", "gain"), before, "is not interactive");
  ASSERT_TRUE(g.setInteractive("gain", "gain", true));
  ASSERT_TRUE(g.setInteractive("gain2", "gain", true));
  EXPECT_TRUE(g.connect("gain", "gain", "gain2", "gain"));
  EXPECT_TRUE(g.connect("gain2", "gain", "gain", "gain"));  // linked both ways: no data cycle
  ASSERT_TRUE(g.setInteractive("gain", "gain", false));  // drops its parameter connections
  EXPECT_TRUE(g.describe().connections.empty());
}

TEST_F(Connect, DisconnectRemovesOnlyThatConnection) {
  link(g, "src", "out", "gain", "in");
  link(g, "src", "out", "sink", "in");
  ASSERT_TRUE(g.disconnect("src", "out", "gain", "in"));
  ASSERT_EQ(g.describe().connections.size(), 1u);
  EXPECT_EQ(g.describe().connections[0].to_node, "sink");
  auto st = g.disconnect("src", "out", "gain", "in");
  EXPECT_THAT(st.message(), HasSubstr("not connected"));
}

TEST_F(Connect, RemovingANodeRemovesItsConnections) {
  link(g, "src", "out", "gain", "in");
  link(g, "gain", "out", "sink", "in");
  link(g, "counter", "every_n", "gain", "disable");
  ASSERT_TRUE(g.removeNode("gain"));
  EXPECT_TRUE(g.describe().connections.empty());
  EXPECT_THAT(g.removeNode("gain").message(), HasSubstr("no node named 'gain'"));
  link(g, "src", "out", "sink", "in");  // the freed input takes a new source
}

}  // namespace
