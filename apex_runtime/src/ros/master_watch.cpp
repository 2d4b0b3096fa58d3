#include "master_watch.hpp"

#include <ros/connection_manager.h>
#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <ros/service_manager.h>
#include <ros/xmlrpc_manager.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include <map>
#include <set>
#include <vector>

namespace apex {
namespace ros_host {
namespace {

using XmlRpc::XmlRpcValue;

/** A master API call; its answer's value, or nothing when the master is gone or says no. */
bool callMaster(const std::string& method, const std::vector<std::string>& args, XmlRpcValue& payload) {
  XmlRpcValue request, response;
  request[0] = ros::this_node::getName();
  for (std::size_t i = 0; i < args.size(); ++i) request[static_cast<int>(i + 1)] = args[i];
  return ros::master::execute(method, request, response, payload, false);
}

/** A call to this process's own XML-RPC server: the node API the master and other nodes call. */
bool callSelf(const char* method, XmlRpcValue& request, XmlRpcValue& response) {
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(ros::XMLRPCManager::instance()->getServerURI(), host, port)) return false;
  XmlRpc::XmlRpcClient self(host.c_str(), static_cast<int>(port), "/");
  return self.execute(method, request, response) && response.getType() == XmlRpcValue::TypeArray && response.size() >= 3 &&
         static_cast<int>(response[0]) == 1;
}

/** [topic, type] pairs this process publishes or subscribes (roscpp keeps its lists private;
 *  its node API tells them). */
std::vector<std::pair<std::string, std::string>> ownTopics(const char* method) {
  std::vector<std::pair<std::string, std::string>> out;
  XmlRpcValue request, response;
  request[0] = ros::this_node::getName();
  if (!callSelf(method, request, response)) return out;
  XmlRpcValue& list = response[2];
  for (int i = 0; list.getType() == XmlRpcValue::TypeArray && i < list.size(); ++i)
    out.emplace_back(static_cast<std::string>(list[i][0]), static_cast<std::string>(list[i][1]));
  return out;
}

/** topic → the publishers (their XML-RPC URIs) this process receives from now (getBusInfo). */
std::map<std::string, std::set<std::string>> connectedPublishers() {
  std::map<std::string, std::set<std::string>> out;
  XmlRpcValue request, response;
  request[0] = ros::this_node::getName();
  if (!callSelf("getBusInfo", request, response)) return out;
  XmlRpcValue& links = response[2];
  for (int i = 0; links.getType() == XmlRpcValue::TypeArray && i < links.size(); ++i)
    if (links[i].size() >= 5 && static_cast<std::string>(links[i][2]) == "i")
      out[static_cast<std::string>(links[i][4])].insert(static_cast<std::string>(links[i][1]));
  return out;
}

}  // namespace

MasterWatch::MasterWatch(std::function<void()> registered_again, std::function<std::uint64_t()> services_version, double period)
    : registered_again_(std::move(registered_again)),
      period_(period),
      // (read now: once roscpp shuts down, its TCP server is gone and asking for its port aborts)
      service_api_("rosrpc://" + ros::network::getHost() + ":" +
                   std::to_string(ros::ConnectionManager::instance()->getTCPPort())) {
  services_version_ = std::move(services_version);
  seen_version_ = listed_version_ = services_version_();
  ros::param::get("/run_id", run_id_);
  (void)check();  // the master's process
  listServices();  // what it lists of this node now
  thread_ = std::thread([this] { run(); });
}

MasterWatch::~MasterWatch() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void MasterWatch::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, std::chrono::duration<double>(period_), [this] { return stop_; })) {
    lock.unlock();
    try {
      // (shutting down, roscpp unregisters everything itself: nothing is lost then)
      if (!ros::isShuttingDown() && check() && !ros::isShuttingDown()) {
        const std::string what = registerAgain();
        listServices();  // the new master's list
        if (registered_again_) registered_again_();
        ROS_WARN_STREAM_NAMED("apex", "a new ROS master (run id '" << run_id_ << "'): registered " << what << " again");
      }
    } catch (const XmlRpc::XmlRpcException& e) {  // an answer of an unexpected shape: next time
      ROS_WARN_STREAM_NAMED("apex", "checking the ROS master: " << e.getMessage());
    }
    lock.lock();
  }
}

bool MasterWatch::check() {
  XmlRpcValue pid;
  if (!callMaster("getPid", {}, pid) || pid.getType() != XmlRpcValue::TypeInt) return false;  // no master: the next one
  // Lost: another master process, or a roscore started again (its run id, set soon after it
  // starts). Whatever of ours registered with the new master meanwhile cannot hide the rest.
  bool lost = master_pid_ != 0 && static_cast<int>(pid) != master_pid_;
  master_pid_ = static_cast<int>(pid);
  std::string run_id;
  if (ros::param::get("/run_id", run_id) && run_id != run_id_) {
    lost = lost || !run_id_.empty();
    run_id_ = run_id;
  }
  if (lost) return true;  // services_: what the last master listed, for the new one
  constexpr int kRelistChecks = 300;
  const std::uint64_t version = services_version_();
  const bool settled = version != listed_version_ && version == seen_version_;  // the host made them by now
  seen_version_ = version;
  if (settled || relist_ || ++checks_ % kRelistChecks == 0) {
    listed_version_ = version;
    listServices();
  }
  return false;
}

void MasterWatch::listServices() {
  XmlRpcValue state;
  relist_ = !callMaster("getSystemState", {}, state) || state.getType() != XmlRpcValue::TypeArray || state.size() < 3;
  if (relist_) return;  // again at the next check
  std::set<std::string> listed;
  XmlRpcValue& services = state[2];
  for (int i = 0; services.getType() == XmlRpcValue::TypeArray && i < services.size(); ++i) {
    XmlRpcValue& providers = services[i][1];
    for (int j = 0; providers.getType() == XmlRpcValue::TypeArray && j < providers.size(); ++j)
      if (static_cast<std::string>(providers[j]) == ros::this_node::getName())
        listed.insert(static_cast<std::string>(services[i][0]));
  }
  services_ = std::move(listed);
}

std::string MasterWatch::registerAgain() {
  const std::string api = ros::XMLRPCManager::instance()->getServerURI();
  int publications = 0, subscriptions = 0, services = 0;
  XmlRpcValue payload;
  for (const auto& [topic, type] : ownTopics("getPublications"))
    publications += callMaster("registerPublisher", {topic, type, api}, payload);
  for (const auto& [topic, type] : ownTopics("getSubscriptions")) {
    if (!callMaster("registerSubscriber", {topic, type, api}, payload)) continue;
    ++subscriptions;
    // Connect to the publishers the new master knows, as it tells a node (publisherUpdate), and
    // keep those we receive from now: a list without them would drop their connections, and a
    // publisher in a process that does not register again (a driver) would be lost for good.
    std::set<std::string> publishers = connectedPublishers()[topic];
    for (int i = 0; payload.getType() == XmlRpcValue::TypeArray && i < payload.size(); ++i)
      publishers.insert(static_cast<std::string>(payload[i]));
    XmlRpcValue update, list, response;
    list.setSize(0);
    for (const auto& uri : publishers) list[list.size()] = uri;
    update[0] = "/master", update[1] = topic, update[2] = list;
    (void)callSelf("publisherUpdate", update, response);
  }
  for (const auto& service : services_)  // (those still offered: an edit may have removed one since)
    if (ros::ServiceManager::instance()->lookupServicePublication(service))
      services += callMaster("registerService", {service, service_api_, api}, payload);
  return std::to_string(publications) + " publications, " + std::to_string(subscriptions) + " subscriptions and " +
         std::to_string(services) + " services";
}

}  // namespace ros_host
}  // namespace apex
