// Live edits on the running demo graph (the bag looping inside the graph), as a
// user makes them from the panel or with rosservice: disconnect and reconnect a
// link of the camera chain, delete a node in the middle of it and undo that.
// The overlay must flow again after each repair, and the cloud chain and the
// rest of the camera chain must keep flowing while the chain is cut.
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <apex/AddNode.h>
#include <apex/Connect.h>
#include <apex/RemoveNode.h>
#include <apex/RuntimeStatus.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <thread>

#include "apex_test/ros_client.hpp"

using namespace apex_test;

namespace {

apex::Connect::Request link(const std::string& a, const std::string& ap, const std::string& b, const std::string& bp) {
  apex::Connect::Request r;
  r.from_node = a;
  r.from_port = ap;
  r.to_node = b;
  r.to_port = bp;
  return r;
}

void expectOk(bool success, const std::string& message, const std::string& what) {
  EXPECT_TRUE(success) << what << ": " << message;
}

/** What ~status says `node` waits for ("" if it is not stalled). */
std::string waitingFor(ros::NodeHandle& nh, const std::string& node) {
  apex::RuntimeStatus status;
  EXPECT_TRUE(receive(nh, "/apex/status", status)) << "no ~status";
  for (const auto& n : status.nodes)
    if (n.name == node) return n.waiting_for;
  return "(not listed)";
}

TEST(LiveEdit, TheOverlayKeepsFlowingThroughReconnectsRemovalsAndUndo) {
  ros::NodeHandle nh;
  TopicCounter<sensor_msgs::Image> overlay(nh, "/apex_demo/overlay");
  TopicCounter<sensor_msgs::PointCloud2> cloud(nh, "/apex_demo/points");
  ASSERT_TRUE(overlay.flows()) << "the demo graph never published an overlay";

  // Disconnect and connect again a link in the middle of the chain, several times.
  for (int round = 0; round < 5; ++round) {
    auto off = call<apex::Connect>("disconnect", link("gray", "image", "threshold", "image"));
    expectOk(off.success, off.message, "disconnect gray -> threshold");
    auto on = call<apex::Connect>("connect", link("gray", "image", "threshold", "image"));
    expectOk(on.success, on.message, "connect gray -> threshold");
    ASSERT_TRUE(overlay.flows()) << "the overlay stopped after reconnecting gray -> threshold (round " << round << ")";
  }

  // Cut the chain and leave it cut: the cloud chain and the image chain up to the cut keep going.
  auto off = call<apex::Connect>("disconnect", link("gray", "image", "threshold", "image"));
  expectOk(off.success, off.message, "disconnect gray -> threshold");
  EXPECT_TRUE(cloud.flows()) << "the cloud chain stopped while the camera chain was cut";
  EXPECT_TRUE(keepsFiring(nh, "gray")) << "the camera chain before the cut stopped";
  std::string why;
  for (int i = 0; i < 10 && why.empty(); ++i) why = waitingFor(nh, "threshold");
  EXPECT_EQ(why, "cut off: input 'image' is not connected");
  auto on = call<apex::Connect>("connect", link("gray", "image", "threshold", "image"));
  expectOk(on.success, on.message, "connect gray -> threshold");
  ASSERT_TRUE(overlay.flows()) << "the overlay stopped after a long cut";

  // Delete a node in the middle of the chain, then undo it as the panel does.
  apex::RemoveNode::Request rm;
  rm.name = "morphology";
  auto removed = call<apex::RemoveNode>("remove_node", rm);
  expectOk(removed.success, removed.message, "remove morphology");
  EXPECT_TRUE(cloud.flows()) << "the cloud chain stopped after removing morphology";
  EXPECT_TRUE(keepsFiring(nh, "rotate")) << "the camera chain stopped after removing morphology";
  apex::AddNode::Request add;
  add.type = "apex_nodes/Morphology";
  add.name = "morphology";
  add.thread_group = "vision";
  add.parameters = "{operation: close, shape: rect, kernel_size: 7, iterations: 1}";
  auto added = call<apex::AddNode>("add_node", add);
  expectOk(added.success, added.message, "add morphology back");
  auto in = call<apex::Connect>("connect", link("threshold", "image", "morphology", "image"));
  expectOk(in.success, in.message, "connect threshold -> morphology");
  auto out = call<apex::Connect>("connect", link("morphology", "image", "blobs", "image"));
  expectOk(out.success, out.message, "connect morphology -> blobs");
  EXPECT_TRUE(overlay.flows()) << "the overlay stopped after removing morphology and undoing it";
  EXPECT_TRUE(cloud.flows());
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_live_edit");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
