// A graph loaded at start-up runs: its nodes are there and data flows (the
// counter's firings grow), whether the runtime is a node or a nodelet.
#include <apex/RuntimeStatus.h>
#include <gmock/gmock.h>

#include <condition_variable>

#include "apex_test/ros_client.hpp"

using namespace apex_test;

namespace {

/** Firings of `node` in the next ~status message. */
std::uint64_t firings(ros::NodeHandle& nh, const std::string& node) {
  std::mutex m;
  std::condition_variable cv;
  std::uint64_t n = 0;
  bool got = false;
  auto sub = nh.subscribe<apex::RuntimeStatus>("/apex/status", 1, [&](const apex::RuntimeStatus::ConstPtr& s) {
    std::lock_guard<std::mutex> l(m);
    for (const auto& ns : s->nodes) if (ns.name == node) n = ns.firings;
    got = true;
    cv.notify_all();
  });
  std::unique_lock<std::mutex> l(m);
  EXPECT_TRUE(cv.wait_for(l, std::chrono::seconds(20), [&] { return got; })) << "no ~status";
  return n;
}

TEST(Startup, TheGraphFileIsLoadedAndRuns) {
  auto graph = call<apex::GetGraph>("get_graph");
  ASSERT_TRUE(graph.success);
  ASSERT_EQ(graph.graph.nodes.size(), 3u);
  EXPECT_EQ(graph.graph.nodes[0].name, "clock");
  EXPECT_EQ(graph.graph.nodes[2].thread_group, "counting");
  EXPECT_EQ(graph.graph.connections.size(), 2u);
  ros::NodeHandle nh;
  const auto first = firings(nh, "count");
  std::uint64_t later = first;
  for (int i = 0; i < 10 && later <= first; ++i) later = firings(nh, "count");  // a new status every 0.5 s
  EXPECT_GT(later, first);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_startup");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
