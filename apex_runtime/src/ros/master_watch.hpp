// Survives a restart of the ROS master. roscpp registers publishers, subscribers and services
// with the master once, when they are made; a new master knows none of them, so tools started
// afterwards (rosservice, rviz, rostopic) would never find the runtime. MasterWatch notices a new
// master, or lost registration, and registers again everything this process offers and wants.
#pragma once

#include <condition_variable>
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
  explicit MasterWatch(std::function<void()> registered_again, double period = 1.0);
  /** @brief Stops the thread (within one check). */
  ~MasterWatch();

  MasterWatch(const MasterWatch&) = delete;
  MasterWatch& operator=(const MasterWatch&) = delete;

 private:
  void run();
  /** Asks the master what it lists of this node (one getSystemState) and remembers its services;
   *  true if registration was lost: a service the last master listed, still offered, is not
   *  listed now, or the master's run id changed. False while no master answers. */
  bool check();
  /** Registers every publication, subscription and service of the process again; the count. */
  std::string registerAgain();

  std::function<void()> registered_again_;
  double period_;
  std::string service_api_;  // where this process's services answer (rosrpc://host:port)
  std::string run_id_;  // of the master last seen; "" if it had none yet
  std::set<std::string> services_;  // this node's, as masters listed them, while still offered
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace ros_host
}  // namespace apex
