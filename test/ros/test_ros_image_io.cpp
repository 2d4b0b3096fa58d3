// ImagePublisher and ImageSubscriber nodes on separate thread groups all set
// up their image_transport at once (pluginlib and class_loader underneath are
// not thread-safe). Every node must reach ROS, none may fail, the runtime must
// live: at start-up, and when all their topics change at once, round after round.
#include <apex/GetGraph.h>
#include <apex/LoadGraph.h>
#include <apex/SetParameter.h>
#include <gmock/gmock.h>

#include <set>

#include "apex_test/ros_client.hpp"

using namespace apex_test;

namespace {

constexpr int kPairs = 6;  // as in test/data/image_io.yaml
std::string g_graph;  // that file

std::string topic(int round, int i) {
  return round == 0 ? "/image_io/img" + std::to_string(i) : "/image_io/r" + std::to_string(round) + "/img" + std::to_string(i);
}

/** Topics that /apex publishes, and those it subscribes, as the master sees them. */
void apexTopics(std::set<std::string>& published, std::set<std::string>& subscribed) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", args, result, payload, false)) return;
  auto collect = [](XmlRpc::XmlRpcValue& list, std::set<std::string>& out) {
    for (int t = 0; t < list.size(); ++t)
      for (int n = 0; n < list[t][1].size(); ++n)
        if (std::string(list[t][1][n]) == "/apex") out.insert(std::string(list[t][0]));
  };
  collect(payload[0], published);
  collect(payload[1], subscribed);
}

/** Until every pair of the round has its publisher and subscriber registered (the master has no
 *  event to wait on: it is asked again every 20 ms). Returns what is still missing. */
std::string waitForRound(int round) {
  std::string missing;
  const auto deadline = ros::WallTime::now() + ros::WallDuration(30);
  do {
    std::set<std::string> published, subscribed;
    apexTopics(published, subscribed);
    missing.clear();
    for (int i = 0; i < kPairs; ++i) {
      if (!published.count(topic(round, i))) missing += " publisher " + topic(round, i);
      if (!subscribed.count(topic(round, i))) missing += " subscriber " + topic(round, i);
    }
    if (missing.empty()) return missing;
    ros::WallDuration(0.02).sleep();
  } while (ros::WallTime::now() < deadline);
  return missing;
}

std::string nodeErrors() {
  std::string errors;
  for (const auto& n : call<apex::GetGraph>("get_graph").graph.nodes)
    if (!n.error.empty()) errors += "\n" + n.name + ": " + n.error;
  return errors;
}

TEST(ImageIo, EveryNodeReachesRosAtStartUp) {
  EXPECT_EQ(waitForRound(0), "");
  EXPECT_EQ(nodeErrors(), "");
}

TEST(ImageIo, TheGraphLoadedAgainAndAgain) {
  apex::LoadGraph::Request load;
  load.path = g_graph;
  for (int round = 0; round < 10; ++round) {
    auto res = call<apex::LoadGraph>("load_graph", load);
    ASSERT_TRUE(res.success) << res.message;
    ASSERT_EQ(waitForRound(0), "") << "load " << round;
    ASSERT_EQ(nodeErrors(), "") << "load " << round;
  }
}

TEST(ImageIo, AllTopicsChangedAtOnceRoundAfterRound) {
  for (int round = 1; round <= 8; ++round) {
    // One call per node; each returns once the value is taken, and the nodes apply it on
    // their own thread groups, so the twelve re-subscriptions and re-advertisements overlap.
    for (int k = 0; k < 2 * kPairs; ++k) {
      apex::SetParameter::Request r;
      r.node = (k % 2 ? "sub" : "pub") + std::to_string(k / 2);
      r.parameter = "topic";
      r.value = topic(round, k / 2).substr(1);
      auto res = call<apex::SetParameter>("set_parameter", r);
      ASSERT_TRUE(res.success) << r.node << ": " << res.message;
    }
    ASSERT_EQ(waitForRound(round), "") << "round " << round;
    ASSERT_EQ(nodeErrors(), "") << "round " << round;
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_image_io");
  if (argc < 2) {
    std::fprintf(stderr, "usage: test_ros_image_io GRAPH\n");
    return 2;
  }
  g_graph = argv[1];
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
