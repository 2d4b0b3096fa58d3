#include "apex_nodes/remote_workers.hpp"

#include <mutex>
#include <utility>

namespace apex_nodes {
namespace tuning {
namespace {

std::mutex& transportMutex() {
  static std::mutex m;
  return m;
}
std::shared_ptr<RemoteWorkers>& transport() {
  static std::shared_ptr<RemoteWorkers> t;
  return t;
}

}  // namespace

std::shared_ptr<RemoteWorkers> remoteWorkers() {
  std::lock_guard<std::mutex> lock(transportMutex());
  return transport();
}

std::shared_ptr<RemoteWorkers> setRemoteWorkers(std::shared_ptr<RemoteWorkers> t) {
  std::lock_guard<std::mutex> lock(transportMutex());
  return std::exchange(transport(), std::move(t));
}

}  // namespace tuning
}  // namespace apex_nodes
