// ~balance (issue #37): thread groups proposed from each node's measured time, and applied on
// request through set_thread_group (one binary with test_ros_services.cpp, one services.test).
#include <apex/Balance.h>

#include <chrono>
#include <future>
#include <map>
#include <vector>

#include "services_fixture.hpp"

using namespace services_test;

namespace {

/** clock (in group "a") -> first -> second (in "b"), and `idle`, a Relay fed by nothing. */
void addChain() {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "clock", "{rate: 500}", "a").success);
  ASSERT_TRUE(addNode("apex_nodes/Relay", "first", "", "b").success);
  ASSERT_TRUE(addNode("apex_nodes/Relay", "second", "", "b").success);
  ASSERT_TRUE(addNode("apex_nodes/Relay", "idle", "", "b").success);
  ASSERT_TRUE(connectPorts("connect", "clock", "count", "first", "in").success);
  ASSERT_TRUE(connectPorts("connect", "first", "out", "second", "in").success);
}

/** Waits until ~status says `node` is cut off (what balance does not wait for). */
bool reportedCutOff(ros::NodeHandle& nh, const std::string& node) {
  for (int i = 0; i < 20; ++i) {
    apex::RuntimeStatus status;
    if (!receive(nh, "/apex/status", status)) return false;
    for (const auto& n : status.nodes)
      if (n.name == node && n.waiting_for.rfind("cut off", 0) == 0) return true;
  }
  return false;
}

std::map<std::string, std::string> groupsNow() {
  std::map<std::string, std::string> out;
  for (const auto& n : call<apex::GetGraph>("get_graph").graph.nodes) out[n.name] = n.thread_group;
  return out;
}

TEST_F(Services, BalanceMeasuresFramesAndProposesAGroupForEveryNode) {
  addChain();
  ros::NodeHandle nh;
  ASSERT_TRUE(reportedCutOff(nh, "idle"));  // it never fires: measuring must not wait for it
  const std::string before = graphText();
  apex::Balance::Request req;
  req.frames = 20, req.groups = 2;
  const auto res = call<apex::Balance>("balance", req);
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_EQ(graphText(), before);  // only proposed
  EXPECT_THAT(res.nodes, ::testing::UnorderedElementsAre("clock", "first", "second", "idle"));
  ASSERT_EQ(res.groups.size(), res.nodes.size());
  ASSERT_EQ(res.stage_ms.size(), res.stage_groups.size());
  EXPECT_LE(res.stage_groups.size(), 2u);
  EXPECT_GE(res.expected_speedup, 1.0);
  EXPECT_THAT(res.message, HasSubstr("expect"));
  EXPECT_THAT(res.message, HasSubstr(res.stage_groups.front()));
}

TEST_F(Services, BalanceAppliedMovesEveryNodeToItsProposedGroup) {
  addChain();
  apex::Balance::Request req;
  req.frames = 0, req.groups = 2, req.apply = true;  // the times measured so far
  const auto res = call<apex::Balance>("balance", req);
  ASSERT_TRUE(res.success) << res.message;
  const auto now = groupsNow();
  for (std::size_t i = 0; i < res.nodes.size(); ++i) EXPECT_EQ(now.at(res.nodes[i]), res.groups[i]) << res.nodes[i];
  // the nodes were in two groups ("a": the clock, "b": the relays): one stage (relays take
  // microseconds, less than a group boundary costs) keeps its majority's
  if (res.stage_groups.size() == 1) EXPECT_EQ(res.stage_groups.front(), "b");
}

// clock -> three nodes of 20 ms each (apex_test/Busy: waits, so the stages overlap on any machine):
// cut after the first or after the second, the period is 40 ms either way, so both are tried.
TEST_F(Services, BalanceWithTrialsRunsTheClosestPlacementsAndLeavesTheGroups) {
  ASSERT_TRUE(addNode("apex_nodes/Clock", "clock", "{rate: 100}").success);
  std::string prev = "clock", port = "count";
  for (const char* name : {"b1", "b2", "b3"}) {
    ASSERT_TRUE(addNode("apex_test/Busy", name, "{seconds: 0.02}").success);
    ASSERT_TRUE(connectPorts("connect", prev, port, name, "in").success);
    prev = name, port = "out";
  }
  const std::string before = graphText();
  apex::Balance::Request req;
  req.frames = 3, req.groups = 2, req.trials = 3;
  const auto res = call<apex::Balance>("balance", req);
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_THAT(res.message, HasSubstr("tried the 2 closest placements for 3 frames each"));
  EXPECT_EQ(res.stage_groups.size(), 2u);
  EXPECT_EQ(graphText(), before);  // the trials' groups are undone; only proposed
}

TEST_F(Services, BalanceRefusesWhatItCannotDoAndSaysWhy) {
  addChain();
  const std::string before = graphText();
  apex::Balance::Request req;
  req.groups = -1;
  auto res = call<apex::Balance>("balance", req);
  EXPECT_FALSE(res.success);
  EXPECT_THAT(res.message, HasSubstr("groups must be 0"));
  apex::Control::Request pause;
  pause.command = "pause";
  ASSERT_TRUE(call<apex::Control>("control", pause).paused);
  req.groups = 2, req.frames = 10, req.apply = true;
  res = call<apex::Balance>("balance", req);
  EXPECT_FALSE(res.success);
  EXPECT_THAT(res.message, HasSubstr("paused"));
  EXPECT_EQ(graphText(), before);
  pause.command = "resume";
  EXPECT_FALSE(call<apex::Control>("control", pause).paused);
}

TEST_F(Services, BalancesWaitingForFramesHoldNoThreadOfTheOtherServices) {
  // Four balances once held every service thread: a get_graph sent 1 s later waited 29 s.
  addChain();
  std::vector<std::future<apex::Balance::Response>> balances;
  for (int i = 0; i < 4; ++i)
    balances.push_back(std::async(std::launch::async, [] {
      apex::Balance::Request req;
      req.frames = 1000000, req.groups = 2;  // more frames than it would ever wait for
      return call<apex::Balance>("balance", req);
    }));
  const auto since = std::chrono::steady_clock::now();
  int answered = 0;
  while (std::chrono::steady_clock::now() - since < std::chrono::seconds(2)) {
    EXPECT_EQ(call<apex::GetGraph>("get_graph").graph.nodes.size(), 4u);
    apex::Control::Request resume;  // (it runs: it goes on running)
    resume.command = "resume";
    EXPECT_TRUE(call<apex::Control>("control", resume).success);
    ++answered;
  }
  int done = 0;
  for (auto& b : balances) done += b.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
  EXPECT_EQ(done, 0) << "the other services answered only once a balance gave up (" << answered << " calls answered)";
  // Frames stop: the balance measuring gives up, those waiting their turn are refused at once.
  apex::RemoveNode::Request remove;
  remove.name = "clock";
  ASSERT_TRUE(call<apex::RemoveNode>("remove_node", remove).success);
  for (auto& b : balances) {
    const auto res = b.get();
    EXPECT_FALSE(res.success);
    EXPECT_THAT(res.message, ::testing::AnyOf(HasSubstr("the frames stopped"), HasSubstr("no node runs"))) << res.message;
  }
}

}  // namespace
