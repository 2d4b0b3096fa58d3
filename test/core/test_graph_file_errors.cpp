// The YAML graph format's error cases: messages with line numbers, and
// all-or-nothing loading that leaves the graph untouched.
#include <gtest/gtest.h>

#include <string>

#include "apex/core/graph.hpp"
#include "apex/core/graph_file.hpp"
#include "apex/core/param.hpp"
#include "apex_test/graph_file_helpers.hpp"
#include "apex_test/test_nodes.hpp"

namespace {

using namespace apex;
using apex_test::add;
using apex_test::buildRichGraph;
using apex_test::Contains;
using apex_test::TempDir;
using apex_test::testRegistry;
using apex_test::writeFile;

// ---------------------------------------------------------------- (c) errors leave the graph untouched

class GraphFileErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    buildRichGraph(graph);
    before = formatGraphText(graph.describe());
  }
  /** Loads `text` from a file; expects failure and an untouched graph; returns the message. */
  std::string loadFails(const std::string& text) {
    const std::string path = dir.file("bad.yaml");
    writeFile(path, text);
    auto r = loadGraphFile(graph, path);
    EXPECT_FALSE(r) << "loaded:\n" << text;
    EXPECT_TRUE(Contains(r.message(), {path}));
    EXPECT_EQ(formatGraphText(graph.describe()), before);
    EXPECT_EQ(graph.size(), 6u);
    return r.message();
  }
  TempDir dir;
  Graph graph{testRegistry()};
  std::string before;
};

TEST_F(GraphFileErrors, MalformedYamlNamesTheLine) {
  const std::string indent = loadFails("apex_graph: 1\nnodes:\n  - name: g\n     type: test/Gain\n");
  EXPECT_TRUE(Contains(indent, {"line 4"})) << indent;
  const std::string flow = loadFails("apex_graph: 1\nnodes:\n  - name: g\n    type: test/Gain\n    parameters: {gain: [1, 2}\n");
  EXPECT_TRUE(Contains(flow, {"line 5"})) << flow;
  const std::string open = loadFails("apex_graph: 1\nnodes: [\n  {name: a, type: test/Gain},\n  {name: b\n");
  EXPECT_TRUE(Contains(open, {"line "})) << open;
}

TEST_F(GraphFileErrors, EmptyFileHasNoLineZero) {
  const std::string msg = loadFails("");
  EXPECT_TRUE(Contains(msg, {"apex_graph"}));
  EXPECT_EQ(msg.find("line 0"), std::string::npos) << msg;  // lines count from 1
}

TEST_F(GraphFileErrors, NotAGraphFileOrWrongVersion) {
  EXPECT_TRUE(Contains(loadFails("nodes: []\nconnections: []\n"), {"apex_graph"}));
  EXPECT_TRUE(Contains(loadFails("- just\n- a list\n"), {"apex_graph"}));
  const std::string msg = loadFails("apex_graph: 3\nnodes: []\n");
  EXPECT_TRUE(Contains(msg, {"line 1", "format 3", "not supported", "formats 1 to 2"})) << msg;
  EXPECT_TRUE(Contains(loadFails("apex_graph: one\n"), {"line 1", "version number"}));
}

TEST_F(GraphFileErrors, UnknownKeyInANodeNamesKeyAndLine) {
  const std::string msg = loadFails("apex_graph: 1\nnodes:\n  - name: g\n    type: test/Gain\n    colour: red\n");
  EXPECT_TRUE(Contains(msg, {"line 5", "node 'g'", "unknown key 'colour'", "thread_group", "parameters"})) << msg;
  EXPECT_TRUE(Contains(loadFails("apex_graph: 1\nnodez: []\n"), {"line 2", "unknown key 'nodez'"}));
  EXPECT_TRUE(Contains(loadFails("apex_graph: 1\nnodes:\n  - {name: g, type: test/Gain}\n"
                                 "connections:\n  - {from: g/out, to: g/in, via: x}\n"),
                       {"line 5", "unknown key 'via'"}));
}

TEST_F(GraphFileErrors, ConnectionToAnUnknownPortListsThePorts) {
  const std::string msg = loadFails(
      "apex_graph: 1\nnodes:\n  - name: f\n    type: test/Feeder\n  - name: g\n    type: test/Gain\n"
      "connections:\n  - {from: f/out, to: g/input}\n");
  EXPECT_TRUE(Contains(msg, {"line 8", "f/out", "g/input", "node 'g'", "inputs: in", "parameters: gain"})) << msg;
  const std::string out = loadFails(
      "apex_graph: 1\nnodes:\n  - {name: f, type: test/Feeder}\n  - {name: g, type: test/Gain}\n"
      "connections:\n  - {from: f/output, to: g/in}\n");
  EXPECT_TRUE(Contains(out, {"line 6", "'output'", "outputs: out"})) << out;
  EXPECT_TRUE(Contains(loadFails("apex_graph: 1\nnodes:\n  - {name: f, type: test/Feeder}\n"
                                 "connections:\n  - {from: f/out, to: nobody/in}\n"),
                       {"line 5", "no node named 'nobody'"}));
  EXPECT_TRUE(Contains(loadFails("apex_graph: 1\nconnections:\n  - {from: f, to: g/in}\n"), {"line 3", "node/port"}));
}

TEST_F(GraphFileErrors, CycleInTheFile) {
  const std::string msg = loadFails(
      "apex_graph: 1\nnodes:\n  - {name: a, type: test/Gain}\n  - {name: b, type: test/Gain}\n"
      "connections:\n  - {from: a/out, to: b/in}\n  - {from: b/out, to: a/in}\n");
  EXPECT_TRUE(Contains(msg, {"line 7", "cycle"})) << msg;
}

TEST_F(GraphFileErrors, BadNodeSettingsNameTheNodeLine) {
  EXPECT_TRUE(Contains(loadFails("apex_graph: 1\nnodes:\n  - name: g\n    type: test/Gain\n"
                                 "    parameters: {gain: 500}\n"),
                       {"line 3", "'g'", "'gain'", "out of range"}));
  EXPECT_TRUE(Contains(loadFails("apex_graph: 1\nnodes:\n  - {name: g, type: test/Gain, parameters: {gian: 1}}\n"),
                       {"line 3", "no parameter 'gian'"}));
  EXPECT_TRUE(Contains(loadFails("apex_graph: 1\nnodes:\n  - {name: g, type: test/Gain}\n"
                                 "  - {name: g, type: test/Gain}\n"),
                       {"line 4", "already exists"}));
  EXPECT_TRUE(
      Contains(loadFails("apex_graph: 1\nnodes:\n  - {name: g, type: test/Gain, enabled: perhaps}\n"), {"line 3", "'enabled'"}));
  EXPECT_TRUE(Contains(loadFails("apex_graph: 1\nnodes:\n  - {name: g}\n"), {"line 3", "'type' is missing"}));
  EXPECT_TRUE(
      Contains(loadFails("apex_graph: 1\nnodes:\n  - {name: g, type: test/Gain, interactive: [nope]}\n"), {"line 3", "'nope'"}));
}

/** A node type with a pair parameter, for map-valued parameters in files. */
struct Sized : Node {
  static Manifest manifest() { return Manifest("has a size").param(param::pair("size", 1, 2)); }
  void process() override {}
};

TEST_F(GraphFileErrors, WhatTheFormatDoesNotUseIsRefused) {
  const std::string head = "apex_graph: 1\nnodes:\n";
  EXPECT_TRUE(Contains(loadFails(head + "  - name: a\n    type: test/Relay\n    parameters: {x: 1}\n    parameters: {x: 2}\n"),
                       {"line 6", "node 'a': the key 'parameters' appears twice"}));
  EXPECT_TRUE(Contains(loadFails(head + "  - {name: a, type: test/Gain, parameters: {gain: 1, gain: 2}}\n"),
                       {"the parameter 'gain' appears twice"}));
  EXPECT_TRUE(Contains(loadFails("apex_graph: 1\napex_graph: 1\nnodes: []\n"), {"the key 'apex_graph' appears twice"}));
  EXPECT_TRUE(Contains(loadFails(head + "  - {name: a, type: test/Relay}\n---\napex_graph: 1\nnodes: []\n"),
                       {"one YAML document, and this is a second one"}));
  EXPECT_TRUE(Contains(loadFails(head + "  - {name: a, type: test/Relay, ui: !!binary aGVsbG8=}\n"),
                       {"line 3", "the tag 'tag:yaml.org,2002:binary' is not part of the graph format"}));
  EXPECT_TRUE(Contains(loadFails(head + "  - {name: !custom a, type: test/Relay}\n"), {"the tag '!custom'"}));
}

TEST_F(GraphFileErrors, MalformedTextThatHungTheYamlParserIsRefusedAtOnce) {
  // Found by fuzz_graph_file: YAML::LoadAll (yaml-cpp 0.7) never returned on a lone comma.
  for (const std::string text : {",", ",,,,ap", "apex_graph: 1\n,", "[,]", "{:"}) EXPECT_FALSE(loadFails(text).empty()) << text;
}

TEST_F(GraphFileErrors, SizesBeyondTheLimitsAreRefusedNotRunOutOfMemory) {
  std::string bomb = "a: &a [x, x, x, x, x, x, x, x, x, x]\n";  // ten to the ninth values through aliases
  for (char c = 'b'; c <= 'j'; ++c)
    bomb += std::string(1, c) + ": &" + c + " [*" + char(c - 1) + ", *" + char(c - 1) + ", *" + char(c - 1) + ", *" +
            char(c - 1) + ", *" + char(c - 1) + ", *" + char(c - 1) + ", *" + char(c - 1) + ", *" + char(c - 1) + ", *" +
            char(c - 1) + ", *" + char(c - 1) + "]\n";
  EXPECT_TRUE(Contains(loadFails(bomb), {"more than " + std::to_string(apex::kMaxYamlNodes) + " values"}));
  const std::string deep = std::string(10000, '[') + std::string(10000, ']');
  EXPECT_FALSE(loadFails("apex_graph: 1\nnodes:\n  - {name: a, type: test/Relay, ui: " + deep + "}\n").empty());
  std::string many = "apex_graph: 1\nnodes: [";
  for (int i = 0; i < 30000; ++i) many += "{}, ";
  EXPECT_TRUE(Contains(loadFails(many + "]\n"), {"30000 nodes, over the limit of 20000"}));
  const std::string lots(100000, 'x');
  EXPECT_TRUE(Contains(loadFails("apex_graph: 1\nnodes:\n  - {name: a, type: test/Relay, ui: " + lots + "}\n"),
                       {"a value of 100000 characters, over the limit of 65536"}));
}

TEST_F(GraphFileErrors, NestingTooDeepIsRefusedBeforeTheTextIsParsed) {
  // yaml-cpp queues a token for each bracket of a line before it builds anything (4 MiB of "["
  // took a gigabyte): a scan refuses such text first, naming where.
  const std::string ui = "apex_graph: 1\nnodes:\n  - {name: a, type: test/Relay, ui: ";
  EXPECT_TRUE(Contains(loadFails(ui + std::string(100000, '[')), {"line 3", "nested deeper than 32 levels"}));
  std::string maps;
  for (int i = 0; i < 1000; ++i) maps += "{a: ";
  EXPECT_TRUE(Contains(loadFails(ui + maps), {"line 3", "nested deeper than 32 levels"}));
  std::string dashes = "apex_graph: 1\nnodes:\n";
  for (int i = 0; i < 1000; ++i) dashes += "- ";
  EXPECT_TRUE(Contains(loadFails(dashes + "x\n"), {"line 3", "nested deeper than 32 levels"}));
  EXPECT_TRUE(Contains(loadFails("apex_graph: 1\nnodes: []\n---\n" + std::string(100000, '{')),
                       {"line 4", "nested deeper than 32 levels"}));
  std::string block = "apex_graph: 1\nnodes:\n  - name: a\n    type: test/Relay\n    ui:\n";
  for (int i = 0; i < 40; ++i) block += std::string(6 + 2 * i, ' ') + "k:\n";
  EXPECT_TRUE(Contains(loadFails(block), {"nested deeper than 32 levels"}));
}

TEST_F(GraphFileErrors, BracketsInTextCommentsAndQuotesAreNotNesting) {
  const std::string many(40, '['), braces(40, '{');
  const std::string text = "apex_graph: 1\n# " + many + " a comment\nnodes:\n  - name: a  # " + braces +
                           "\n    type: test/Relay\n    ui:\n      note: |\n        " + many + "\n        " + braces +
                           "\n\n        - - - - - - - - - - - - - - - - - - - - - - - - - - - - - - - - - - - -\n"
                           "      folded: >-\n        " +
                           many + "\n      quoted: '" + many + " '' " + braces + "'\n      double: \"" + many + " \\\" " +
                           braces + "\"\n      plain: a " + many + "\n      list: [\"" + many + "\", '" + braces +
                           "', {b: [1, 2]}]  # " + many + "\n";
  const std::string path = dir.file("brackets.yaml");
  writeFile(path, text);
  auto r = loadGraphFile(graph, path);
  ASSERT_TRUE(r) << r.message() << "\n" << text;
  EXPECT_EQ(graph.size(), 1u);  // (every shipped graph loads: services.test's EveryShippedGraphLoads)
}

TEST_F(GraphFileErrors, ALoneCarriageReturnIsTextAndACrLfEndsALine) {
  // yaml-cpp reads "\r\n" as a line break and a "\r" alone as text; the scan must agree, or
  // text that parses as one value is refused as nesting (found by fuzz_param_text).
  std::string dashes;
  for (int i = 0; i < 100; ++i) dashes += "-\r?\r";
  auto value = param::text("s", "x").parse(dashes);
  ASSERT_TRUE(value) << value.message();
  EXPECT_EQ(toText(value.value()), dashes);
  std::string deep = "apex_graph: 1\r\nnodes:\r\n";
  for (int i = 0; i < 1000; ++i) deep += "- ";
  EXPECT_TRUE(Contains(loadFails(deep + "x\r\n"), {"line 3", "nested deeper than 32 levels"}));
  std::string crlf = "apex_graph: 1\r\nnodes:\r\n  - name: a\r\n    type: test/Relay\r\n    ui:\r\n";
  for (int i = 0; i < 20; ++i) crlf += std::string(6 + 2 * i, ' ') + "k:\r\n" + std::string(6 + 2 * i, ' ') + "\r\n";
  const std::string path = dir.file("crlf.yaml");
  writeFile(path, crlf + std::string(46, ' ') + "k: 1\r\n");
  auto r = loadGraphFile(graph, path);
  ASSERT_TRUE(r) << r.message();
}

TEST(GraphFileErrorsMapValue, ParameterMapMissingAKeyIsAnErrorNotAnException) {
  NodeRegistry registry = testRegistry();
  ASSERT_TRUE(registry.add<Sized>("test/Sized"));
  Graph g(registry);
  add(g, "test/Sized", "before");
  const std::string prior = formatGraphText(g.describe());
  auto parsed = parseGraphText("apex_graph: 1\nnodes:\n  - {name: s, type: test/Sized, parameters: {size: {first: 1}}}\n");
  ASSERT_TRUE(parsed) << parsed.message();
  Result<LoadReport> r = Status::error("not run");
  EXPECT_NO_THROW(r = g.load(parsed.value()));
  EXPECT_FALSE(r);
  EXPECT_TRUE(Contains(r.message(), {"line 3", "'size'"})) << r.message();
  EXPECT_EQ(formatGraphText(g.describe()), prior);
  Result<std::string> set = Status::error("not run");
  EXPECT_NO_THROW(set = g.setParameter("before", "size", "{second: 5}"));
  EXPECT_FALSE(set);
}

}  // namespace
