// Survives a restart of the ROS master. roscpp registers publishers, subscribers and services
// with the master once, when they are made; a new master knows none of them, so tools started
// afterwards (rosservice, rviz, rostopic) would never find the runtime. MasterWatch notices a new
// master, or lost registration, and registers again everything this process offers and wants.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <thread>

namespace apex {
namespace ros_host {

class MasterWatch {
 public:
  /** @brief Checks the master every `period` seconds on a thread of its own (calls to a master
   *  that is gone wait, and must not hold up services or data). `registered_again` runs on that
   *  thread after a new master has been given everything: the host sets its parameters again. */
  /** `services_version` grows when this process may offer other services (an edit made or
   *  removed some); it is read on that thread and must outlive the watch. */
  MasterWatch(std::function<void()> registered_again, std::function<std::uint64_t()> services_version, double period = 1.0);
  /** @brief Stops the thread (within one check). */
  ~MasterWatch();

  MasterWatch(const MasterWatch&) = delete;
  MasterWatch& operator=(const MasterWatch&) = delete;

 private:
  void run();
  /** True if registration was lost: the master's process (getPid) or its run id is not the one
   *  last seen. False while no master answers. Costs the same whatever the graph's size: what
   *  the master lists of this node (getSystemState, all of the system) is asked for only once
   *  the services version has changed and then stayed put for a check, or every `kRelistChecks`
   *  checks (another nodelet's services). */
  bool check();
  /** Remembers the services the master lists for this node (one getSystemState). */
  void listServices();
  /** Registers every publication, subscription and service of the process again; the count. */
  std::string registerAgain();

  std::function<void()> registered_again_;
  double period_;
  std::string service_api_;  // where this process's services answer (rosrpc://host:port)
  std::string run_id_;  // of the master last seen; "" if it had none yet
  int master_pid_ = 0;  // of the master last seen; 0 if none answered yet
  std::set<std::string> services_;  // this node's, as the last master listed them
  std::function<std::uint64_t()> services_version_;
  std::uint64_t seen_version_ = 0, listed_version_ = 0;
  bool relist_ = false;  // the last list failed: again
  int checks_ = 0;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace ros_host
}  // namespace apex
