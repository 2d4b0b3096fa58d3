// What every services test shares: the service types, a client's calls (apex_test/ros_client.hpp),
// and the Services fixture, which starts each test from an empty graph.
#pragma once

#include <apex/AddNode.h>
#include <apex/Connect.h>
#include <apex/Control.h>
#include <apex/FireSlot.h>
#include <apex/GetGraph.h>
#include <apex/GraphState.h>
#include <apex/Group.h>
#include <apex/Inspect.h>
#include <apex/ListNodeTypes.h>
#include <apex/LoadGraph.h>
#include <apex/GetNodeProfile.h>
#include <apex/RemoveNode.h>
#include <apex/RenameNode.h>
#include <apex/SaveGraph.h>
#include <apex/SetEnabled.h>
#include <apex/SetInteractive.h>
#include <apex/SetParameter.h>
#include <apex/SetThreadGroup.h>
#include <apex/SetUi.h>
#include <apex/Ungroup.h>
#include <gmock/gmock.h>
#include <ros/package.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Int32.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "apex_test/ros_client.hpp"

using namespace apex_test;
using ::testing::HasSubstr;
using ::testing::Not;

namespace services_test {

inline std::string tempPath(const std::string& name) {
  return "/tmp/apex_test_services_" + std::to_string(getpid()) + "_" + name;
}

inline void writeFile(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

inline apex::AddNode::Response addNode(const std::string& type, const std::string& name, const std::string& params = "",
                                       const std::string& group = "") {
  apex::AddNode::Request req;
  req.type = type;
  req.name = name;
  req.parameters = params;
  req.thread_group = group;
  return call<apex::AddNode>("add_node", req);
}

inline apex::Connect::Response connectPorts(const std::string& service, const std::string& a, const std::string& ap,
                                            const std::string& b, const std::string& bp) {
  apex::Connect::Request req;
  req.from_node = a, req.from_port = ap, req.to_node = b, req.to_port = bp;
  return call<apex::Connect>(service, req);
}

struct Services : ::testing::Test {
  void SetUp() override {  // every test starts from an empty graph
    const std::string empty = tempPath("empty.yaml");
    writeFile(empty, "apex_graph: 1\nnodes: []\nconnections: []\n");
    apex::LoadGraph::Request req;
    req.path = empty;
    ASSERT_TRUE(call<apex::LoadGraph>("load_graph", req).success);
  }
  /** The call was refused with `what` in its message and the graph did not change. */
  template <class Res>
  void refused(const Res& res, const std::string& before, const std::string& what) {
    EXPECT_FALSE(res.success);
    EXPECT_THAT(res.message, HasSubstr(what));
    EXPECT_EQ(graphText(), before);
  }
};

}  // namespace services_test
