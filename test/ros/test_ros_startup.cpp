// A graph loaded at start-up runs: its nodes are there and data flows (the
// counter's firings grow), whether the runtime is a node or a nodelet.
#include <gmock/gmock.h>

#include "apex_test/ros_client.hpp"

using namespace apex_test;

namespace {

TEST(Startup, TheGraphFileIsLoadedAndRuns) {
  auto graph = call<apex::GetGraph>("get_graph");
  ASSERT_TRUE(graph.success);
  ASSERT_EQ(graph.graph.nodes.size(), 3u);
  EXPECT_EQ(graph.graph.nodes[0].name, "clock");
  EXPECT_EQ(graph.graph.nodes[2].thread_group, "counting");
  EXPECT_EQ(graph.graph.connections.size(), 2u);
  ros::NodeHandle nh;
  EXPECT_TRUE(keepsFiring(nh, "count"));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_startup");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
