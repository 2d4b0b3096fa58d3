// rosrun apex apex_runtime_node _graph:=my_graph.yaml
#include <ros/ros.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <memory>

#include "apex/ros/runtime_host.hpp"

namespace {
// SIGTERM (roslaunch's second signal, systemd's and docker's first) stops the graph
// as SIGINT does: roscpp only handles SIGINT. requestShutdown() only sets a flag.
void onTerm(int) { ros::requestShutdown(); }
}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "apex");
  std::signal(SIGTERM, onTerm);
  ros::NodeHandle nh, pnh("~");
  ros::AsyncSpinner spinner(4);  // services answer concurrently; the graph is thread-safe
  spinner.start();
  auto host = std::make_unique<apex::ros_host::RuntimeHost>(nh, pnh);
  ros::waitForShutdown();  // SIGINT/SIGTERM: roscpp shuts down (unregisters), then the host stops every group
  // A node inside a long process() cannot be interrupted: wait for it at most 1 s, then exit
  // without it (roslaunch would escalate to SIGKILL after 15 s, docker after 10).
  auto stopped = std::async(std::launch::async, [&host] { host.reset(); });
  if (stopped.wait_for(std::chrono::milliseconds(1000)) == std::future_status::timeout) {
    std::fprintf(stderr, "[apex] a node is still inside process() 1 s after shutdown; exiting without it\n");
    std::fflush(nullptr);
    std::_Exit(0);
  }
  spinner.stop();
  return 0;
}
