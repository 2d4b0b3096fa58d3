// apex_nodelet_manager: a nodelet manager, as `rosrun nodelet nodelet manager`, that stops cleanly.
//
// Debian 12's nodelet (1.10) destroys a manager's nodelets before the bonds of the `nodelet load`
// processes attached to them; a bond broken in its destructor then unloads a nodelet that is gone.
// A manager stopped while a loader is attached crashes (SIGSEGV, or SIGABRT with boost::lock_error),
// whatever the nodelet (test/ros/nodelet_interrupts.sh shows it with a trivial one); the loader
// then waits for its bond to time out. This manager, on SIGINT, SIGTERM or `rosnode kill`, first
// unloads every nodelet through its own unload_nodelet service, as a loader would: each bond is
// broken on purpose, so each loader exits at once; and it never destroys the Loader.
#include <ros/ros.h>
// (ros.h first: nodelet's headers need it)
#include <nodelet/NodeletUnload.h>
#include <nodelet/loader.h>

#include <cstdio>
#include <cstdlib>

#include "stop_request.hpp"

using namespace apex::ros_host;

int main(int argc, char** argv) {
  noteStopSignals();
  ros::init(argc, argv, "manager", ros::init_options::NoSigintHandler);
  ros::NodeHandle private_nh("~");
  noteStopCalls();
  // Never destroyed: a load that arrives while this manager stops would leave a bond for the
  // destructor. The process ends with it.
  auto* loader = new nodelet::Loader(private_nh);  // load_nodelet, unload_nodelet, list; num_worker_threads
  ros::AsyncSpinner spinner(1);  // as `nodelet manager` spins: nodelets on the global queue see one thread
  spinner.start();
  while (!g_stop_requested && ros::ok()) nap();
  // Through the service, which breaks each bond; without a master to find it, directly (the bond
  // stays, and the Loader with it). Again until none is left: a load may have been under way.
  ros::ServiceClient unload = private_nh.serviceClient<nodelet::NodeletUnload>("unload_nodelet");
  for (int pass = 0; pass < 5; ++pass) {
    const auto names = loader->listLoadedNodelets();  // waits for a load under way
    if (names.empty()) break;
    for (const auto& name : names) {
      nodelet::NodeletUnload call;
      call.request.name = name;
      if (!unload.call(call) || !call.response.success) loader->unload(name);
    }
  }
  ros::shutdown();  // no more calls, callbacks or messages
  spinner.stop();
  std::fflush(nullptr);
  std::_Exit(0);  // not through the static destructors: roscpp's would meet the bond threads still there
}
