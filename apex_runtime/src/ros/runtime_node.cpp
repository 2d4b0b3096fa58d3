// rosrun apex apex_runtime_node _graph:=my_graph.yaml
#include <ros/ros.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <memory>

#include "apex/ros/runtime_host.hpp"

namespace {
// SIGINT and SIGTERM (roslaunch's second signal, systemd's and docker's first) stop the graph.
// They only set a flag: main() then stops in an order of its own (roscpp's handler would shut
// down with the spinner's threads still running, and those spin on its disabled queue, taking
// the cores from the thousands of calls that unregister a big graph's topics and services).
std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }

/** Runs `fn` for at most 1 s: a node inside a long process(), or a service call that takes
 *  long, cannot be interrupted; then the process exits without it (roslaunch would escalate to
 *  SIGKILL after 15 s, docker after 10). */
template <class F>
void atMostASecond(const char* what, F fn) {
  auto done = std::async(std::launch::async, fn);
  if (done.wait_for(std::chrono::milliseconds(1000)) == std::future_status::ready) return;
  std::fprintf(stderr, "[apex] %s 1 s after shutdown; exiting without it\n", what);
  std::fflush(nullptr);
  std::_Exit(0);
}
}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "apex", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  ros::NodeHandle nh, pnh("~");
  ros::AsyncSpinner spinner(4);  // services answer concurrently; the graph is thread-safe
  spinner.start();
  auto host = std::make_unique<apex::ros_host::RuntimeHost>(nh, pnh);
  while (!g_stop && ros::ok()) ros::WallDuration(0.05).sleep();  // (not ok: rosnode kill)
  // No more callbacks, then roscpp unregisters everything, then the host stops every group.
  atMostASecond("a service call is still running", [&spinner] { spinner.stop(); });
  ros::shutdown();
  atMostASecond("a node is still inside process()", [&host] { host.reset(); });
  return 0;
}
