// Soak: a seeded random sequence of live edits on the running demo graph (the
// bag looping inside the graph), made through the runtime's services as a user
// makes them from the panel: disconnect and connect links, remove nodes and add
// them back, move nodes between thread groups, disable and enable them, change
// the threshold. Every 25 edits, and at the end, the graph is restored and the
// overlay and the cloud must flow again. APEX_SOAK_SEED replays a run,
// APEX_SOAK_EDITS sets its length.
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <apex/AddNode.h>
#include <apex/Connect.h>
#include <apex/GetGraph.h>
#include <apex/RemoveNode.h>
#include <apex/RuntimeStatus.h>
#include <apex/SetEnabled.h>
#include <apex/SetParameter.h>
#include <apex/SetThreadGroup.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "apex_test/ros_client.hpp"

using namespace apex_test;

namespace {

struct Link {
  const char* from_node;
  const char* from_port;
  const char* to_node;
  const char* to_port;
};

/** The `connections:` of graphs/paper_pipeline.yaml. */
const std::vector<Link> kLinks = {
    {"bag", "camera_image_raw", "rotate", "image"},   {"rotate", "image", "gray", "image"},
    {"gray", "image", "threshold", "image"},          {"threshold", "image", "morphology", "image"},
    {"morphology", "image", "blobs", "image"},        {"rotate", "image", "overlay", "image"},
    {"blobs", "regions", "overlay", "regions"},       {"overlay", "image", "overlay_out", "image"},
    {"bag", "camera_points", "passthrough", "cloud"}, {"passthrough", "cloud", "voxels", "cloud"},
    {"voxels", "cloud", "cloud_out", "cloud"},
};

struct NodeSpec {
  const char* name;
  const char* type;
  const char* group;
  const char* parameters;  // YAML flow mapping, as AddNode takes it
};

/** The camera chain and cloud chain nodes as graphs/paper_pipeline.yaml declares them. */
const std::vector<NodeSpec> kNodes = {
    {"rotate", "apex_nodes/Rotate", "vision", "{angle: 1.5707963267948966}"},
    {"gray", "apex_nodes/ColorConvert", "vision", "{conversion: BGR2GRAY}"},
    {"threshold", "apex_nodes/AdaptiveThreshold", "vision",
     "{max_value: 255.0, method: gaussian, threshold_type: binary_inv, block_size: 101, c: 25.0}"},
    {"morphology", "apex_nodes/Morphology", "vision", "{operation: close, shape: rect, kernel_size: 7, iterations: 1}"},
    {"blobs", "apex_nodes/BlobDetection", "vision", "{min_area: 1500, max_area: 20000, connectivity: \"8\"}"},
    {"overlay", "apex_nodes/DrawRegions", "vision", ""},
    {"passthrough", "apex_nodes/PassThrough", "cloud", "{field: z, limits: [0.0, 3.0]}"},
    {"voxels", "apex_nodes/VoxelGrid", "cloud", "{leaf_size: 0.05}"},
};

const std::vector<std::string> kGroups = {"vision", "cloud", "default", "extra"};

apex::Connect::Request request(const Link& l) {
  apex::Connect::Request r;
  r.from_node = l.from_node;
  r.from_port = l.from_port;
  r.to_node = l.to_node;
  r.to_port = l.to_port;
  return r;
}

apex::AddNode::Request request(const NodeSpec& n) {
  apex::AddNode::Request r;
  r.type = n.type;
  r.name = n.name;
  r.thread_group = n.group;
  r.parameters = n.parameters;
  return r;
}

/** An unsigned number from the environment, `fallback()` if it is not set. */
template <class Fallback>
unsigned long fromEnv(const char* name, Fallback fallback) {
  const char* text = std::getenv(name);
  return text && *text ? std::strtoul(text, nullptr, 10) : fallback();
}

/** One random edit; refusals are fine. `removed` holds the indices in kNodes of the nodes removed so far. */
void randomEdit(std::mt19937& rng, std::set<std::size_t>& removed) {
  auto pick = [&rng](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  const std::size_t k = pick(kNodes.size());
  const NodeSpec& node = kNodes[k];
  switch (pick(7)) {
    case 0:
      call<apex::Connect>("disconnect", request(kLinks[pick(kLinks.size())]));
      break;
    case 1:
      call<apex::Connect>("connect", request(kLinks[pick(kLinks.size())]));
      break;
    case 2: {
      apex::RemoveNode::Request rm;
      rm.name = node.name;
      if (call<apex::RemoveNode>("remove_node", rm).success) removed.insert(k);
      break;
    }
    case 3: {  // add back a removed node if there is one, else try adding one that is there
      std::size_t back = k;
      if (!removed.empty()) back = *std::next(removed.begin(), static_cast<long>(pick(removed.size())));
      if (call<apex::AddNode>("add_node", request(kNodes[back])).success) removed.erase(back);
      break;
    }
    case 4: {
      apex::SetThreadGroup::Request grp;
      grp.node = node.name, grp.group = kGroups[pick(kGroups.size())];
      call<apex::SetThreadGroup>("set_thread_group", grp);
      break;
    }
    case 5: {
      apex::SetEnabled::Request en;
      en.node = node.name, en.enabled = pick(2) == 1;
      call<apex::SetEnabled>("set_enabled", en);
      break;
    }
    default: {
      apex::SetParameter::Request set;
      set.node = "threshold", set.parameter = "c";
      set.value = std::to_string(std::uniform_real_distribution<double>(5, 40)(rng));
      call<apex::SetParameter>("set_parameter", set);
      break;
    }
  }
}

/** Undoes what the edits left: re-adds missing nodes, enables them, moves them back, connects every link. */
void restore(std::set<std::size_t>& removed) {
  std::set<std::string> present;
  for (const auto& n : call<apex::GetGraph>("get_graph").graph.nodes) present.insert(n.name);
  for (const auto& n : kNodes) {
    if (!present.count(n.name)) {
      auto added = call<apex::AddNode>("add_node", request(n));
      EXPECT_TRUE(added.success) << "re-adding " << n.name << ": " << added.message;
    }
    apex::SetEnabled::Request en;
    en.node = n.name, en.enabled = true;
    auto enabled = call<apex::SetEnabled>("set_enabled", en);
    EXPECT_TRUE(enabled.success) << "enabling " << n.name << ": " << enabled.message;
    apex::SetThreadGroup::Request grp;
    grp.node = n.name, grp.group = n.group;
    auto moved = call<apex::SetThreadGroup>("set_thread_group", grp);
    EXPECT_TRUE(moved.success) << "moving " << n.name << " back to " << n.group << ": " << moved.message;
  }
  removed.clear();
  for (const auto& l : kLinks) {
    auto on = call<apex::Connect>("connect", request(l));
    EXPECT_TRUE(on.success || on.message.find("already connected") != std::string::npos)
        << "connecting " << l.from_node << "/" << l.from_port << " -> " << l.to_node << "/" << l.to_port << ": " << on.message;
  }
}

/** What ~status says about every node that waits for something or is in error. */
std::string stalls(ros::NodeHandle& nh) {
  apex::RuntimeStatus status;
  if (!receive(nh, "/apex/status", status)) return " no ~status";
  std::ostringstream out;
  for (const auto& n : status.nodes) {
    if (n.waiting_for.empty() && n.error.empty()) continue;
    out << "\n  " << n.name << " (" << n.state << ")";
    if (!n.waiting_for.empty()) out << ": " << n.waiting_for;
    if (!n.error.empty()) out << "; error: " << n.error;
  }
  const std::string text = out.str();
  return text.empty() ? " no node waits or is in error" : text;
}

TEST(Soak, TheDemoGraphFlowsAgainAfterRandomLiveEdits) {
  const auto seed = static_cast<std::uint32_t>(fromEnv("APEX_SOAK_SEED", [] { return std::random_device{}(); }));
  const long edits = static_cast<long>(fromEnv("APEX_SOAK_EDITS", [] { return 300ul; }));
  std::printf("soak: APEX_SOAK_SEED=%u APEX_SOAK_EDITS=%ld\n", static_cast<unsigned>(seed), edits);
  std::fflush(stdout);
  SCOPED_TRACE("APEX_SOAK_SEED=" + std::to_string(seed));
  std::mt19937 rng(seed);

  ros::NodeHandle nh;
  TopicCounter<sensor_msgs::Image> overlay(nh, "/apex_demo/overlay");
  TopicCounter<sensor_msgs::PointCloud2> cloud(nh, "/apex_demo/points");
  ASSERT_TRUE(overlay.flows()) << "the demo graph never published an overlay";
  ASSERT_TRUE(cloud.flows()) << "the demo graph never published a cloud";

  std::set<std::size_t> removed;
  for (long i = 1; i <= edits; ++i) {
    randomEdit(rng, removed);
    if (i % 25 != 0 && i != edits) continue;
    restore(removed);
    const bool images = overlay.flows(2, 20);
    const bool points = cloud.flows(2, 20);
    ASSERT_TRUE(images && points) << "after " << i << " edits (seed " << seed << ") and a restore, "
                                  << (images ? "" : "/apex_demo/overlay ") << (points ? "" : "/apex_demo/points ")
                                  << "stopped; ~status:" << stalls(nh);
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_soak");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
