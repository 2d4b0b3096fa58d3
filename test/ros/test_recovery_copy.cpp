// The recovery copy's rules without a master (recovery.hpp): when it is written (after a burst
// of edits, on a clock the test drives), when it is not or is removed (the graph as saved, an
// empty graph, a clean stop), and a previous run's copy set aside and offered, never replaced.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "apex_test/graph_file_helpers.hpp"  // TempDir, readFile
#include "recovery.hpp"

namespace {

using apex::ros_host::Recovery;
using apex_test::readFile;
using namespace std::chrono_literals;
namespace fs = std::filesystem;

const std::string kSaved = "apex_graph: 2\nnodes:\n  - {name: a, type: apex_nodes/Clock}\n";
const std::string kEdited = kSaved + "  - {name: b, type: apex_nodes/Clock}\n";

class RecoveryCopy : public ::testing::Test {
 protected:
  std::function<Recovery::Snapshot()> graph(const std::string& text, std::size_t nodes = 2) {
    return [text, nodes] { return Recovery::Snapshot{text, nodes}; };
  }
  /** A burst of edits ending in revision `revision` at `at`, then the quiet that writes it. */
  void settle(Recovery& r, std::uint64_t revision, const std::string& text, Recovery::Clock::time_point at,
              std::size_t nodes = 2) {
    r.tick(revision, graph(text, nodes), at);
    r.tick(revision, graph(text, nodes), at + timing_.quiet);
  }
  std::string copy() const { return folder_ + "/robot1_apex.yaml"; }

  apex_test::TempDir home_;
  const std::string folder_ = home_.file("recovery");  // made by Recovery
  const Recovery::Clock::time_point t0_ = Recovery::Clock::now();
  const Recovery::Timing timing_;
};

TEST_F(RecoveryCopy, IsNamedAfterTheRuntimesNode) {
  EXPECT_EQ(Recovery::fileName("/apex"), "apex");
  EXPECT_EQ(Recovery::fileName("/robot1/apex"), "robot1_apex");
}

TEST_F(RecoveryCopy, IsWrittenWholeOnceTheEditsPauseAndWithinASecondOfAnEdit) {
  EXPECT_LE(timing_.quiet, timing_.at_most);
  EXPECT_LE(timing_.at_most, 900ms) << "a copy within a second of any edit, on a 100 ms tick";
  Recovery r(folder_, "/robot1/apex");
  r.saved({kSaved, 1, 0});
  r.tick(7, graph(kEdited), t0_);
  r.tick(7, graph(kEdited), t0_ + timing_.quiet - 1ms);
  EXPECT_FALSE(fs::exists(copy())) << "written in the middle of a burst";
  r.tick(7, graph(kEdited), t0_ + timing_.quiet);
  EXPECT_EQ(readFile(copy()), kEdited);
}

TEST_F(RecoveryCopy, EditsThatGoOnAreWrittenAtMostASecondApart) {
  Recovery r(folder_, "/robot1/apex");
  r.saved({kSaved, 1, 0});
  const auto step = timing_.quiet / 2;
  int revision = 1;
  for (auto t = 0ms; t < timing_.at_most; t += step) r.tick(revision++, graph(kEdited), t0_ + t);
  EXPECT_FALSE(fs::exists(copy()));
  r.tick(revision, graph(kEdited), t0_ + timing_.at_most);
  EXPECT_EQ(readFile(copy()), kEdited);
}

TEST_F(RecoveryCopy, WhatNodesReportOfThemselvesIsNoEditAndWritesNoCopy) {
  // A playing bag changes the graph's text (its frame) many times a second, its edit revision not.
  Recovery r(folder_, "/robot1/apex");
  r.saved({kSaved + "# frame 1\n", 1, 5});
  for (int frame = 2; frame < 200; ++frame)
    r.tick(5, graph(kSaved + "# frame " + std::to_string(frame) + "\n"), t0_ + frame * 100ms);
  EXPECT_FALSE(fs::exists(copy())) << "a copy of the graph as saved, but for the player's frame";
  EXPECT_FALSE(r.unsaved());
  r.tick(6, graph(kEdited + "# frame 200\n"), t0_ + 20s);  // an edit, while it plays
  r.tick(6, graph(kEdited + "# frame 203\n"), t0_ + 20s + timing_.quiet);
  EXPECT_EQ(readFile(copy()), kEdited + "# frame 203\n");
  EXPECT_TRUE(r.unsaved());
}

TEST_F(RecoveryCopy, TheGraphAsSavedOrEmptyHasNoCopy) {
  Recovery r(folder_, "/robot1/apex");
  r.saved({kSaved, 1, 0});
  settle(r, 1, kSaved, t0_);
  EXPECT_FALSE(fs::exists(copy())) << "a copy of the graph as loaded";
  settle(r, 2, kEdited, t0_ + 2s);
  ASSERT_TRUE(fs::exists(copy()));
  r.saved({kEdited, 2, 0});  // save_graph
  EXPECT_FALSE(fs::exists(copy())) << "a save left the copy";
  settle(r, 3, "apex_graph: 2\n", t0_ + 4s, 0);
  EXPECT_FALSE(fs::exists(copy())) << "a copy of an empty graph (New)";
}

TEST_F(RecoveryCopy, ACleanStopRemovesItAndWritesNoMore) {
  Recovery r(folder_, "/robot1/apex");
  r.saved({kSaved, 1, 0});
  settle(r, 1, kEdited, t0_);
  ASSERT_TRUE(fs::exists(copy()));
  r.close();
  EXPECT_FALSE(fs::exists(copy()));
  settle(r, 2, kEdited + "  - {name: c, type: apex_nodes/Clock}\n", t0_ + 2s);
  EXPECT_FALSE(fs::exists(copy())) << "written after the stop";
}

TEST_F(RecoveryCopy, APreviousRunsCopyIsOfferedAndNeverReplacedByThisRunsOwn) {
  fs::create_directories(folder_);
  std::ofstream(copy()) << kEdited;  // a run killed with unsaved edits
  Recovery r(folder_, "/robot1/apex");
  const auto offer = r.offer();
  ASSERT_TRUE(offer);
  EXPECT_EQ(offer->nodes, 2u);
  EXPECT_GT(offer->written_ns, 0);
  EXPECT_EQ(readFile(offer->path), kEdited);
  r.saved({kSaved, 1, 0});
  settle(r, 1, kSaved + "  - {name: x, type: apex_nodes/Clock}\n", t0_);
  r.close();
  EXPECT_EQ(readFile(offer->path), kEdited) << "this run's edits or its stop replaced the offered copy";
  ASSERT_TRUE(r.discard());
  EXPECT_FALSE(fs::exists(offer->path));
  EXPECT_FALSE(r.offer());
  EXPECT_FALSE(r.discard());
}

TEST_F(RecoveryCopy, AnAdoptedCopyIsThisRunsUntilSaved) {
  fs::create_directories(folder_);
  std::ofstream(copy()) << kEdited;
  Recovery r(folder_, "/robot1/apex");
  r.saved({kEdited, 2, 0});  // load_graph of the copy marks it as a file's
  ASSERT_TRUE(r.adopt());  // ... but it is in no file of the user's
  EXPECT_FALSE(r.offer());
  EXPECT_EQ(readFile(copy()), kEdited);
  settle(r, 1, kEdited, Recovery::Clock::now() + 2s);
  EXPECT_EQ(readFile(copy()), kEdited) << "the restored graph lost its copy";
}

}  // namespace
