// While data flows, 200 mixed service calls from 4 client threads: every call
// is answered, the graph is consistent afterwards and data still flows.
#include <apex/AddNode.h>
#include <apex/Connect.h>
#include <apex/FireSlot.h>
#include <apex/Inspect.h>
#include <apex/RemoveNode.h>
#include <apex/SetEnabled.h>
#include <apex/SetParameter.h>
#include <apex/SetThreadGroup.h>
#include <gmock/gmock.h>

#include <atomic>
#include <map>
#include <random>
#include <set>
#include <thread>

#include "apex_test/ros_client.hpp"

using namespace apex_test;

namespace {

/** One persistent connection per service, as a front end keeps them: a call
 *  that fails can only mean the runtime did not answer. */
struct Clients {
  ros::NodeHandle nh;
  std::map<std::string, ros::ServiceClient> open;
  std::vector<std::string> failures;

  template <class Srv>
  bool answered(const std::string& name, typename Srv::Request req, bool& success) {
    auto& c = open[name];
    if (!c) {
      EXPECT_TRUE(ros::service::waitForService(service(name), ros::Duration(20)));
      c = nh.serviceClient<Srv>(service(name), true);
    }
    Srv srv;
    srv.request = req;
    if (!c.call(srv)) {
      failures.push_back(name);
      return false;
    }
    success = srv.response.success;
    return true;
  }
};

/** One client: 50 calls, a mix of edits on its own side path and touches of the main chain. */
void client(int id, std::atomic<int>& answered_calls, std::atomic<int>& unanswered) {
  Clients clients;
  std::mt19937 rng(id);
  const std::string mine = "side" + std::to_string(id);
  int made = 0;
  for (int i = 0; i < 50; ++i) {
    bool ok = false, got = false;
    const std::string node = mine + "_" + std::to_string(made);
    switch (rng() % 8) {
      case 0: {
        apex::AddNode::Request r;
        r.type = "apex_nodes/Counter", r.name = mine + "_" + std::to_string(++made),
        r.thread_group = "g" + std::to_string(rng() % 3);
        got = clients.answered<apex::AddNode>("add_node", r, ok);
        break;
      }
      case 1: {
        apex::Connect::Request r;
        r.from_node = "relay", r.from_port = "out", r.to_node = node, r.to_port = "in";
        got = clients.answered<apex::Connect>(rng() % 2 ? "connect" : "disconnect", r, ok);
        break;
      }
      case 2: {
        apex::SetParameter::Request r;
        r.node = "clock", r.parameter = "rate", r.value = rng() % 4 ? std::to_string(50 + rng() % 100) : "-1";
        got = clients.answered<apex::SetParameter>("set_parameter", r, ok);
        break;
      }
      case 3: {
        apex::SetEnabled::Request r;
        r.node = node, r.enabled = rng() % 2;
        got = clients.answered<apex::SetEnabled>("set_enabled", r, ok);
        break;
      }
      case 4: {
        apex::SetThreadGroup::Request r;
        r.node = rng() % 2 ? node : "relay", r.group = "g" + std::to_string(rng() % 3);
        got = clients.answered<apex::SetThreadGroup>("set_thread_group", r, ok);
        break;
      }
      case 5: {
        apex::FireSlot::Request r;
        r.node = "count", r.slot = "reset";
        got = clients.answered<apex::FireSlot>("fire_slot", r, ok);
        break;
      }
      case 6: {
        apex::Inspect::Request r;
        r.node = "count", r.port = "count", r.enable = rng() % 2;
        got = clients.answered<apex::Inspect>("inspect", r, ok);
        break;
      }
      default: {
        apex::RemoveNode::Request r;
        r.name = node;
        got = clients.answered<apex::RemoveNode>("remove_node", r, ok);
        break;
      }
    }
    (got ? answered_calls : unanswered)++;
  }
  for (const auto& f : clients.failures) ADD_FAILURE() << "client " << id << ": no answer from " << f;
}

TEST(Stress, MixedCallsFromFourClientsWhileDataFlows) {
  ASSERT_TRUE(ros::service::waitForService(service("add_node"), ros::Duration(20)));
  ros::NodeHandle nh;
  std::atomic<int> ok{0}, lost{0};
  std::vector<std::thread> clients;
  for (int id = 0; id < 4; ++id) clients.emplace_back(client, id, std::ref(ok), std::ref(lost));
  for (auto& t : clients) t.join();
  EXPECT_EQ(ok.load(), 200);
  EXPECT_EQ(lost.load(), 0);

  auto graph = call<apex::GetGraph>("get_graph").graph;
  std::set<std::string> names;
  for (const auto& n : graph.nodes) names.insert(n.name);
  for (const char* main : {"clock", "relay", "count"}) EXPECT_TRUE(names.count(main)) << main;
  for (const auto& c : graph.connections) {
    EXPECT_TRUE(names.count(c.from_node)) << c.from_node;
    EXPECT_TRUE(names.count(c.to_node)) << c.to_node;
  }
  EXPECT_TRUE(keepsFiring(nh, "count")) << "data stopped flowing";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_stress");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
