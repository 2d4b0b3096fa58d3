// Survives a restart of the ROS master. roscpp registers publishers, subscribers and services
// with the master once, when they are made; a new master knows none of them, so tools started
// afterwards (rosservice, rviz, rostopic) would never find the runtime. MasterWatch notices a new
// master and registers again everything this process offers and wants.
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
  /** A new master: its run id differs from the last one seen, or it does not know this node. */
  bool masterIsNew();
  /** Registers every publication, subscription and service of the process again; the count. */
  std::string registerAgain();
  /** The services the master lists for this process, remembered for the next master. */
  void rememberServices();

  std::function<void()> registered_again_;
  double period_;
  std::string run_id_;              // of the master last seen; "" if it had none yet
  std::set<std::string> services_;  // this process's, as the master last listed them
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace ros_host
}  // namespace apex
