// The YAML graph format: canonical round trips, files on disk, placeholders for
// unknown types, safe saving and readable text. Error cases: test_graph_file_errors.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "apex/core/graph.hpp"
#include "apex/core/graph_file.hpp"
#include "apex_test/graph_file_helpers.hpp"
#include "apex_test/test_nodes.hpp"

namespace {

using namespace apex;
using apex_test::add;
using apex_test::buildRichGraph;
using apex_test::Contains;
using apex_test::object;
using apex_test::readFile;
using apex_test::TempDir;
using apex_test::testRegistry;
using apex_test::writeFile;
namespace fs = std::filesystem;

// ---------------------------------------------------------------- (a) round trip in memory

TEST(GraphFileRoundTrip, FormatParseLoadFormatGivesTheSameText) {
  Graph g(testRegistry());
  buildRichGraph(g);
  const std::string text = formatGraphText(g.describe());
  EXPECT_TRUE(Contains(text, {"apex_graph: 2", "thread_groups: [vision]", "thread_group: vision", "enabled: false", "gain: 7",
                              "every: 2", "interactive: [gain]", "ui: {x: 10, y: 20}", "{from: g1/gain, to: g2/gain}",
                              "{from: c1/every_n, to: c2/reset}", "{from: feeder/out, to: g1/in}"}))
      << text;

  auto parsed = parseGraphText(text);
  ASSERT_TRUE(parsed) << parsed.message();
  Graph copy(testRegistry());
  auto report = copy.load(parsed.value());
  ASSERT_TRUE(report) << report.message();
  EXPECT_TRUE(report->warnings.empty());
  EXPECT_EQ(copy.size(), 6u);
  EXPECT_EQ(formatGraphText(copy.describe()), text);
}

TEST(GraphFileRoundTrip, LoadedCopyRuns) {
  Graph g(testRegistry());
  buildRichGraph(g);
  Graph copy(testRegistry());
  ASSERT_TRUE(copy.load(parseGraphText(formatGraphText(g.describe())).value()));
  copy.start();
  object<apex_test::Feeder>(copy, "feeder")->feed(2);
  auto* sink = object<apex_test::Collector>(copy, "sink");
  ASSERT_TRUE(sink->waitFor(1));
  ASSERT_TRUE(copy.waitIdle(apex_test::kWait));
  copy.stop();
  ASSERT_EQ(sink->size(), 1u);
  EXPECT_FALSE(sink->messages()[0].isNothing());
}

// ---------------------------------------------------------------- (b) files on disk

TEST(GraphFileDisk, SaveThenLoadRoundTrips) {
  TempDir dir;
  const std::string path = dir.file("graph.yaml");
  Graph g(testRegistry());
  buildRichGraph(g);
  const std::string text = formatGraphText(g.describe());
  auto saved = saveGraphFile(g, path);
  ASSERT_TRUE(saved) << saved.message();
  EXPECT_EQ(readFile(path), text);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"graph.yaml"});  // no temporary left behind

  Graph copy(testRegistry());
  auto report = loadGraphFile(copy, path);
  ASSERT_TRUE(report) << report.message();
  EXPECT_EQ(formatGraphText(copy.describe()), text);
  auto missing = loadGraphFile(copy, dir.file("absent.yaml"));
  ASSERT_FALSE(missing);
  EXPECT_TRUE(Contains(missing.message(), {dir.file("absent.yaml")}));
}

// ---------------------------------------------------------------- (d) unknown types as placeholders

const char* kPlaceholderFile =
    "apex_graph: 1\nthread_groups: [vision]\nnodes:\n  - name: feeder\n    type: test/Feeder\n"
    "  - name: mystery\n"
    "    type: other_pkg/Mystery\n"
    "    thread_group: vision\n"
    "    enabled: false\n"
    "    parameters:\n"
    "      size: [3, 4]\n"
    "      mode: 'fast mode'\n"
    "      nested: {a: 1, b: [x, y]}\n"
    "      ratio: 0.5\n"
    "    interactive: [size, ratio]\n"
    "    ui: {x: 5, y: 6}\n"
    "  - {name: amp, type: test/Gain, interactive: [gain]}\n  - {name: sink, type: test/Collector}\n"
    "connections:\n"
    "  - {from: feeder/out, to: mystery/in}\n"
    "  - {from: mystery/out, to: amp/in}\n"
    "  - {from: mystery/size, to: amp/gain}\n"
    "  - {from: amp/out, to: sink/in}\n";

/** The text of one node's entry in canonical text: from "  - name: <n>" to the next entry or section. */
std::string nodeEntry(const std::string& text, const std::string& name) {
  const auto start = text.find("  - name: " + name + "\n");
  if (start == std::string::npos) return {};
  auto end = text.find("\n  - ", start + 1);
  const auto conns = text.find("\nconnections:", start);
  if (end == std::string::npos || end > conns) end = conns;
  return text.substr(start, end - start);
}

/** The connections of a graph text as "a/out -> b/in", sorted (independent of layout). */
std::vector<std::string> connectionsOf(const std::string& text) {
  std::vector<std::string> out;
  auto d = parseGraphText(text);
  EXPECT_TRUE(d) << d.message();
  if (!d) return out;
  for (const auto& c : d->connections) out.push_back(c.from_node + "/" + c.from_port + " -> " + c.to_node + "/" + c.to_port);
  std::sort(out.begin(), out.end());
  return out;
}

TEST(GraphFilePlaceholder, UnknownTypeLoadsWithAWarning) {
  auto parsed = parseGraphText(kPlaceholderFile);
  ASSERT_TRUE(parsed) << parsed.message();
  Graph g(testRegistry());
  auto report = g.load(parsed.value());
  ASSERT_TRUE(report) << report.message();
  ASSERT_EQ(report->warnings.size(), 1u);
  EXPECT_TRUE(Contains(report->warnings[0], {"line 6", "'mystery'", "other_pkg/Mystery", "placeholder"}));
  EXPECT_EQ(g.size(), 4u);
  EXPECT_EQ(g.nodeType("mystery"), nullptr);
  EXPECT_NE(g.nodeType("amp"), nullptr);
  const NodeDescription mystery = g.describe().nodes.at(1);
  ASSERT_EQ(mystery.name, "mystery");
  EXPECT_TRUE(Contains(mystery.error, {"other_pkg/Mystery"}));
  EXPECT_TRUE(mystery.placeholder) << "describe() should flag a placeholder node";
}

TEST(GraphFilePlaceholder, SaveWritesItBackUnchanged) {
  TempDir dir;
  const std::string canonical = formatGraphText(parseGraphText(kPlaceholderFile).value());
  const std::string in = dir.file("in.yaml"), out = dir.file("out.yaml");
  writeFile(in, canonical);
  Graph g(testRegistry());
  auto report = loadGraphFile(g, in);
  ASSERT_TRUE(report) << report.message();
  ASSERT_TRUE(saveGraphFile(g, out));
  const std::string saved = readFile(out);

  const std::string entry = nodeEntry(canonical, "mystery");
  ASSERT_FALSE(entry.empty()) << canonical;
  EXPECT_TRUE(Contains(entry, {"other_pkg/Mystery", "size: [3, 4]", "fast mode", "nested: {a: 1, b: [x, y]}", "ratio: 0.5",
                               "interactive: [size, ratio]", "ui: {x: 5, y: 6}", "enabled: false", "thread_group: vision"}))
      << entry;
  EXPECT_EQ(nodeEntry(saved, "mystery"), entry) << saved;
  EXPECT_EQ(connectionsOf(saved), connectionsOf(canonical)) << saved;
  EXPECT_EQ(connectionsOf(saved).size(), 4u);

  // And again: a second load → save changes nothing.
  Graph again(testRegistry());
  ASSERT_TRUE(loadGraphFile(again, out));
  EXPECT_EQ(formatGraphText(again.describe()), saved);
}

TEST(GraphFilePlaceholder, ItsParametersCannotBeChangedButItCanBeRemoved) {
  Graph g(testRegistry());
  ASSERT_TRUE(g.load(parseGraphText(kPlaceholderFile).value()));
  const std::string entry = nodeEntry(formatGraphText(g.describe()), "mystery");
  auto r = g.setParameter("mystery", "ratio", "0.7");
  ASSERT_FALSE(r);
  EXPECT_TRUE(Contains(r.message(), {"'mystery'", "other_pkg/Mystery"}));
  EXPECT_EQ(nodeEntry(formatGraphText(g.describe()), "mystery"), entry);
  ASSERT_TRUE(g.removeNode("mystery"));
  const std::string after = formatGraphText(g.describe());
  EXPECT_EQ(after.find("mystery"), std::string::npos) << after;  // its connections went with it
  EXPECT_EQ(connectionsOf(after), std::vector<std::string>{"amp/out -> sink/in"});
}

// ---------------------------------------------------------------- (e) saving safely

TEST(GraphFileSave, MissingOrUnwritableDirectoryNamesThePath) {
  TempDir dir;
  Graph g(testRegistry());
  add(g, "test/Gain", "amp");
  writeFile(dir.file("plain_file"), "x");
  std::vector<std::string> bad = {dir.file("no_such_dir") + "/graph.yaml", dir.file("plain_file") + "/graph.yaml"};
  if (::geteuid() != 0) {  // root writes anywhere: the permission case needs a normal user
    fs::create_directory(dir.path / "locked");
    fs::permissions(dir.path / "locked", fs::perms::owner_read | fs::perms::owner_exec);
    bad.push_back(dir.file("locked") + "/graph.yaml");
  }
  for (const auto& path : bad) {
    auto st = saveGraphFile(g, path);
    EXPECT_FALSE(st) << path;
    EXPECT_TRUE(Contains(st.message(), {path}));
  }
  if (::geteuid() != 0) {
    EXPECT_TRUE(fs::is_empty(dir.path / "locked"));
    fs::permissions(dir.path / "locked", fs::perms::owner_all);
    fs::remove(dir.path / "locked");
  }
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"plain_file"});
}

TEST(GraphFileSave, OverwritingReplacesTheWholeFile) {
  TempDir dir;
  const std::string path = dir.file("graph.yaml");
  writeFile(path, "apex_graph: 2\n# " + std::string(20000, 'x') + "\n");  // a graph file, longer than the new one
  Graph g(testRegistry());
  add(g, "test/Gain", "amp");
  ASSERT_TRUE(saveGraphFile(g, path));
  EXPECT_EQ(readFile(path), formatGraphText(g.describe()));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"graph.yaml"});

  add(g, "test/Collector", "sink");
  ASSERT_TRUE(saveGraphFile(g, path));  // and again over the file just written
  EXPECT_EQ(readFile(path), formatGraphText(g.describe()));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"graph.yaml"});
}

TEST(GraphFileSave, AFailedSaveLeavesTheTargetIntact) {
  TempDir dir;
  Graph g(testRegistry());
  add(g, "test/Gain", "amp");
  // The target is a non-empty directory: it cannot be replaced by a file.
  fs::create_directory(dir.path / "graph.yaml");
  writeFile(dir.file("graph.yaml") + "/keep.txt", "keep");
  auto st = saveGraphFile(g, dir.file("graph.yaml"));
  ASSERT_FALSE(st);
  EXPECT_TRUE(Contains(st.message(), {dir.file("graph.yaml")}));
  EXPECT_TRUE(fs::is_directory(dir.path / "graph.yaml"));
  EXPECT_EQ(readFile(dir.file("graph.yaml") + "/keep.txt"), "keep");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"graph.yaml"});  // the temporary was removed

  if (::geteuid() != 0) {  // an existing file in a read-only directory stays as it was
    const std::string path = dir.file("ro/graph.yaml");
    fs::create_directory(dir.path / "ro");
    writeFile(path, "old content\n");
    fs::permissions(dir.path / "ro", fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_FALSE(saveGraphFile(g, path));
    fs::permissions(dir.path / "ro", fs::perms::owner_all);
    EXPECT_EQ(readFile(path), "old content\n");
  }
}

// ---------------------------------------------------------------- (f) a hand-written file

TEST(GraphFileReadable, SavedTextHasOneBlockEntryPerNodeAndOneLinePerConnection) {
  Graph g(testRegistry());
  buildRichGraph(g);  // list-like values and ui maps must not change the layout of what follows
  ASSERT_TRUE(g.setUi("g2", "{x: 40, y: 20}"));
  const GraphDescription d = g.describe();
  const std::string text = formatGraphText(d);
  std::vector<std::string> lines = {"\nconnections:\n"};
  for (const auto& n : d.nodes) lines.push_back("\n  - name: " + n.name + "\n");
  for (const auto& c : d.connections)
    lines.push_back("\n  - {from: " + c.from_node + "/" + c.from_port + ", to: " + c.to_node + "/" + c.to_port + "}\n");
  EXPECT_TRUE(Contains(text, lines));
}

TEST(GraphFileReadable, HandWrittenFileLoadsAndRuns) {
  TempDir dir;
  const std::string path = dir.file("pipeline.yaml");
  writeFile(path,
            "# A small pipeline, written by hand.\n"
            "apex_graph: 1\n"
            "thread_groups: [vision, io]\n"
            "\n"
            "nodes:\n"
            "  - name: feeder\n"
            "    type: test/Feeder\n"
            "    thread_group: io\n"
            "  - type: test/Gain      # keys in any order\n"
            "    name: amp\n"
            "    thread_group: vision\n"
            "    parameters:\n"
            "      gain: 3\n"
            "    interactive: [gain]\n"
            "    ui: {x: 100, y: 40}\n"
            "  - name: sink\n"
            "    type: test/Collector\n"
            "    enabled: true\n"
            "  - name: counter\n"
            "    type: test/Counter\n"
            "    enabled: false\n"
            "    parameters: {every: 2}\n"
            "  - {name: counter2, type: test/Counter}\n"
            "\n"
            "connections:\n"
            "  - {from: feeder/out, to: amp/in}\n"
            "  - from: amp/out\n"
            "    to: sink/in\n"
            "  - {from: counter/every_n, to: counter2/reset}\n");
  Graph g(testRegistry());
  auto report = loadGraphFile(g, path);
  ASSERT_TRUE(report) << report.message();
  EXPECT_TRUE(report->warnings.empty());

  const GraphDescription d = g.describe();
  ASSERT_EQ(d.nodes.size(), 5u);
  EXPECT_EQ(d.thread_groups, (std::vector<std::string>{"io", "vision"}));
  const NodeDescription& amp = d.nodes[1];
  EXPECT_EQ(amp.name + " " + amp.type + " " + amp.thread_group + " " + amp.ui, "amp test/Gain vision {x: 100, y: 40}");
  EXPECT_EQ(amp.parameters, (std::vector<std::pair<std::string, std::string>>{{"gain", "3"}}));
  EXPECT_EQ(amp.interactive, std::vector<std::string>{"gain"});
  EXPECT_TRUE(d.nodes[2].enabled);
  EXPECT_FALSE(d.nodes[3].enabled);
  EXPECT_EQ(d.nodes[3].parameters, (std::vector<std::pair<std::string, std::string>>{{"every", "2"}}));
  EXPECT_EQ(d.nodes[4].thread_group, "default");
  EXPECT_EQ(d.connections.size(), 3u);

  g.start();
  object<apex_test::Feeder>(g, "feeder")->feed(2);
  auto* sink = object<apex_test::Collector>(g, "sink");
  ASSERT_TRUE(sink->waitFor(1));
  g.stop();
  EXPECT_EQ(sink->ints(), std::vector<int>{6});
}

}  // namespace
