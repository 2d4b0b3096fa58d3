// apex_nodelet_load TYPE MANAGER: loads a nodelet into a manager, as `rosrun nodelet nodelet load
// TYPE MANAGER`, and unloads it when stopped; runtime.launch loads apex/Runtime with it.
//
// Where Debian 12's `nodelet load` (1.10) lingers, this one does not: a SIGINT, a SIGTERM or
// `rosnode kill` is noted at any moment, one during the load call acted on when it returns
// (`nodelet load` takes none during it, so a script's background job, which starts with SIGINT
// ignored, lives on; a second signal ends this one at once); and when the manager goes
// (stopped, or crashed) it exits within a tenth of a second, told by the connection of a persistent
// service client to the manager rather than by a bond that waits 10 s to connect when the manager
// went while it loaded. The bond is kept: a manager that sees this process go unloads the nodelet.
#include <ros/ros.h>
// (ros.h first: nodelet's headers need it)
#include <bondcpp/bond.h>
#include <nodelet/NodeletList.h>
#include <nodelet/NodeletLoad.h>
#include <nodelet/NodeletUnload.h>

#include <random>

#include "stop_request.hpp"

namespace {

using namespace apex::ros_host;

/** The load request: this node's name and remappings become the nodelet's. */
nodelet::NodeletLoad::Request loadRequest(const std::string& type, const std::string& bond_id, int argc, char** argv) {
  nodelet::NodeletLoad::Request req;
  req.name = ros::this_node::getName();
  req.type = type;
  for (const auto& [from, to] : ros::names::getRemappings()) {
    req.remap_source_args.push_back(from);
    req.remap_target_args.push_back(to);
  }
  for (int i = 3; i < argc; ++i) req.my_argv.push_back(argv[i]);  // what follows TYPE MANAGER
  req.bond_id = bond_id;
  return req;
}

}  // namespace

int main(int argc, char** argv) {
  noteStopSignals();  // first: a signal during the load is kept, and acted on after it
  ros::init(argc, argv, "nodelet_load", ros::init_options::NoSigintHandler);  // (removes the ROS arguments)
  if (argc < 3) {
    ROS_ERROR("usage: apex_nodelet_load TYPE MANAGER [ARGS...]  (e.g. apex/Runtime camera_manager)");
    return 2;
  }
  noteStopCalls();
  ros::NodeHandle nh;
  const std::string type = argv[1], manager = argv[2], name = ros::this_node::getName();
  ros::AsyncSpinner spinner(1);
  spinner.start();

  while (!g_stop_requested && !ros::service::exists(manager + "/load_nodelet", false)) nap();  // its manager may come later
  if (g_stop_requested) return 0;
  const std::string bond_id = name + "_" + std::to_string(std::random_device()());
  bond::Bond bond(manager + "/bond", bond_id);
  nodelet::NodeletLoad load;
  load.request = loadRequest(type, bond_id, argc, argv);
  ROS_INFO_STREAM("loading nodelet " << name << " of type " << type << " into manager " << manager);
  if (!ros::service::call(manager + "/load_nodelet", load) || !load.response.success) {
    ROS_ERROR_STREAM("could not load nodelet " << name << " of type " << type << " into manager " << manager
                                               << " (its log says why)");
    return 1;
  }
  bond.start();
  // A persistent connection to the manager: closed the moment the manager's process goes
  ros::ServiceClient manager_link = nh.serviceClient<nodelet::NodeletList>(manager + "/list", true);
  nodelet::NodeletList list;
  bool linked = manager_link.call(list);
  while (!g_stop_requested && !bond.isBroken()) {
    if (linked && !manager_link.isValid()) break;  // the manager's process went
    if (!linked) {
      if (ros::master::check()) {  // a master that answers, and no manager's service to link to: gone
        linked = manager_link.call(list);
        if (!linked) break;
      }  // no master (restarting): the manager may well be there; try again
    }
    nap();
  }
  if (g_stop_requested) {  // stopped: unload, then break the bond (which the manager expects broken)
    nodelet::NodeletUnload unload;
    unload.request.name = name;
    if (!ros::service::call(manager + "/unload_nodelet", unload))
      ROS_WARN_STREAM("could not unload nodelet " << name << ": the manager " << manager << " is gone?");
    bond.breakBond();
  } else {
    ROS_INFO_STREAM("nodelet " << name << " was unloaded, or its manager " << manager << " is gone: done");
  }
  ros::shutdown();
  return 0;
}
