// Many clients at once: 20 service clients, 200 mixed calls each (set_parameter on the demo's
// nodes, get_graph, connect/disconnect on a branch of their own, inspect), while the demo
// graph plays its bag in a loop. Every call is answered, the overlay keeps coming, the
// graph is whole afterwards (many_clients.test).
#include <apex/AddNode.h>
#include <apex/Connect.h>
#include <apex/GetGraph.h>
#include <apex/Inspect.h>
#include <apex/SetParameter.h>
#include <gmock/gmock.h>
#include <sensor_msgs/Image.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <chrono>
#include <map>
#include <random>
#include <set>
#include <thread>

#include "apex_test/ros_client.hpp"

using namespace apex_test;

namespace {

constexpr int kClients = 20;
constexpr int kCallsEach = 200;

/** A client's own connections, one per service, kept open as a front end keeps them. */
class Client {
 public:
  template <class Srv>
  bool call(const std::string& name, const typename Srv::Request& req) {
    auto& c = open_[name];
    if (!c) c = nh_.serviceClient<Srv>(service(name), true);
    Srv srv;
    srv.request = req;
    if (c.call(srv)) return true;
    c = nh_.serviceClient<Srv>(service(name), true);  // one retry on a fresh connection, then it counts
    if (c.call(srv)) return true;
    failures.push_back(name);
    return false;
  }
  std::vector<std::string> failures;

 private:
  ros::NodeHandle nh_;
  std::map<std::string, ros::ServiceClient> open_;
};

/** Counts the demo's overlay frames; waits for more. */
class Overlays {
 public:
  explicit Overlays(ros::NodeHandle& nh)
      : sub_(nh.subscribe<sensor_msgs::Image>("/apex_demo/overlay", 10, [this](const sensor_msgs::ImageConstPtr&) {
          std::lock_guard<std::mutex> lock(m_);
          ++count_;
          cv_.notify_all();
        })) {}
  int count() {
    std::lock_guard<std::mutex> lock(m_);
    return count_;
  }
  bool waitBeyond(int n, double seconds) {
    std::unique_lock<std::mutex> lock(m_);
    return cv_.wait_for(lock, std::chrono::duration<double>(seconds), [&] { return count_ > n; });
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  int count_ = 0;
  ros::Subscriber sub_;
};

void run(int id, std::atomic<int>& answered) {
  Client client;
  std::mt19937 rng(id);
  const std::string branch = "branch_" + std::to_string(id);
  apex::AddNode::Request add;
  add.type = "apex_nodes/Relay", add.name = branch, add.thread_group = "vision";
  if (client.call<apex::AddNode>("add_node", add)) ++answered;
  for (int i = 1; i < kCallsEach; ++i) {
    bool got = false;
    switch (rng() % 5) {
      case 0: {
        apex::SetParameter::Request r;
        r.node = "threshold", r.parameter = "c", r.value = std::to_string(20 + rng() % 10);
        got = client.call<apex::SetParameter>("set_parameter", r);
        break;
      }
      case 1:
        got = client.call<apex::GetGraph>("get_graph", apex::GetGraph::Request());
        break;
      case 2:
      case 3: {
        apex::Connect::Request r;
        r.from_node = "gray", r.from_port = "image", r.to_node = branch, r.to_port = "in";
        got = client.call<apex::Connect>(rng() % 2 ? "connect" : "disconnect", r);
        break;
      }
      default: {
        apex::Inspect::Request r;
        r.node = branch, r.port = "out", r.enable = rng() % 2;
        got = client.call<apex::Inspect>("inspect", r);
        break;
      }
    }
    if (got) ++answered;
  }
  for (const auto& f : client.failures) ADD_FAILURE() << "client " << id << ": no answer from " << f;
}

TEST(ManyClients, TwentyClientsTwoHundredCallsEachWhileTheDemoLoops) {
  ASSERT_TRUE(ros::service::waitForService(service("get_graph"), ros::Duration(30)));
  ros::NodeHandle nh;
  Overlays overlays(nh);
  ASSERT_TRUE(overlays.waitBeyond(0, 30)) << "the demo never sent an overlay";

  std::atomic<int> answered{0};
  const int before = overlays.count();
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> clients;
  for (int id = 0; id < kClients; ++id) clients.emplace_back(run, id, std::ref(answered));
  for (auto& t : clients) t.join();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const int during = overlays.count() - before;
  RecordProperty("calls_answered", answered.load());
  RecordProperty("seconds", std::to_string(seconds));
  RecordProperty("overlays_meanwhile", during);
  EXPECT_EQ(answered.load(), kClients * kCallsEach);
  EXPECT_GT(during, 0) << "no overlay while the clients called";

  auto graph = call<apex::GetGraph>("get_graph").graph;  // whole afterwards
  std::set<std::string> names;
  for (const auto& n : graph.nodes) names.insert(n.name);
  for (const char* main : {"bag", "rotate", "gray", "threshold", "overlay", "overlay_out"})
    EXPECT_TRUE(names.count(main)) << main;
  EXPECT_TRUE(overlays.waitBeyond(overlays.count(), 10)) << "the overlay stopped after the calls";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_many_clients");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
