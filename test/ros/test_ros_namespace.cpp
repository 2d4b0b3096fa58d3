// Nodes get their ROS handles from the host: the demo graph as a nodelet under /robot1, in a
// manager outside that namespace, with a remapped camera topic, subscribes and publishes
// under /robot1, through the remapping, and its frames flow (namespace.test).
#include <gmock/gmock.h>
#include <ros/master.h>
#include <ros/ros.h>
#include <ros/topic.h>
#include <sensor_msgs/Image.h>

#include <map>
#include <set>
#include <string>

namespace {

using Who = std::map<std::string, std::set<std::string>>;  // topic -> nodes

/** Publishers and subscribers by topic, from the master. */
void systemState(Who* publishers, Who* subscribers) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  ASSERT_TRUE(ros::master::execute("getSystemState", args, result, payload, true));
  for (int kind = 0; kind < 2; ++kind) {
    Who& who = kind == 0 ? *publishers : *subscribers;
    for (int i = 0; i < payload[kind].size(); ++i)
      for (int j = 0; j < payload[kind][i][1].size(); ++j)
        who[std::string(payload[kind][i][0])].insert(std::string(payload[kind][i][1][j]));
  }
}

/** The topics on which `node` appears in `who`. */
std::set<std::string> topicsOf(const Who& who, const std::string& node) {
  std::set<std::string> topics;
  for (const auto& [topic, nodes] : who)
    if (nodes.count(node)) topics.insert(topic);
  return topics;
}

TEST(Namespace, TheGraphsTopicsMoveUnderTheNamespaceWithTheNodeletsRemapping) {
  ros::NodeHandle nh;
  auto overlay = ros::topic::waitForMessage<sensor_msgs::Image>("/robot1/apex_demo/overlay", nh, ros::Duration(60));
  ASSERT_TRUE(overlay) << "no overlay frame on /robot1/apex_demo/overlay within 60 s";

  Who publishers, subscribers;
  systemState(&publishers, &subscribers);
  const std::string manager = "/manager";  // every nodelet of a manager is this node to the master
  const auto published = topicsOf(publishers, manager);
  const auto subscribed = topicsOf(subscribers, manager);
  EXPECT_THAT(subscribed, testing::IsSupersetOf({"/robot1/front_camera/image", "/robot1/camera/points"}));
  EXPECT_THAT(published, testing::IsSupersetOf({"/robot1/apex_demo/overlay", "/robot1/apex_demo/points", "/robot1/apex/graph"}));
  // /rosout and /diagnostics are global by ROS's convention (the aggregators listen there)
  for (const auto& topic : published)
    if (topic != "/rosout" && topic != "/diagnostics" && topic.rfind("/manager/", 0) != 0)
      EXPECT_EQ(topic.rfind("/robot1/", 0), 0u) << manager << " publishes " << topic;
  for (const auto& topic : subscribed)
    if (topic != "/clock" && topic.rfind("/manager/", 0) != 0)
      EXPECT_EQ(topic.rfind("/robot1/", 0), 0u) << manager << " subscribes " << topic;
  EXPECT_EQ(subscribed.count("/robot1/camera/image_raw"), 0u) << "the remapping was ignored";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_namespace");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const int failed = RUN_ALL_TESTS();
  spinner.stop();
  ros::shutdown();
  return failed;
}
