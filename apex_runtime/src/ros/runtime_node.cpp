// rosrun apex apex_runtime_node _graph:=my_graph.yaml
#include <ros/ros.h>

#include "apex/ros/runtime_host.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "apex");
  ros::NodeHandle nh, pnh("~");
  ros::AsyncSpinner spinner(4);  // services answer concurrently; the graph is thread-safe
  spinner.start();
  {
    apex::ros_host::RuntimeHost host(nh, pnh);
    ros::waitForShutdown();  // SIGINT: roscpp shuts down, then the host stops every thread group
  }
  spinner.stop();
  return 0;
}
