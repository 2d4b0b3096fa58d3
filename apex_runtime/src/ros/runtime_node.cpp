// rosrun apex apex_runtime_node _graph:=my_graph.yaml
#include <ros/ros.h>

#include <csignal>

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
  {
    apex::ros_host::RuntimeHost host(nh, pnh);
    ros::waitForShutdown();  // SIGINT/SIGTERM: roscpp shuts down, then the host stops every thread group
  }
  spinner.stop();
  return 0;
}
