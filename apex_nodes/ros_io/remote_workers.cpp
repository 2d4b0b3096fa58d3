// The ROS transport of the Optimizer's remote workers (apex_nodes/remote_workers.hpp): each Optimizer of a
// ROS runtime serves `~<name>/evaluate` (srv/EvaluateCandidate.srv) on a callback queue and threads of its
// own, so a candidate under way blocks none of the runtime's services; a candidate sent to another runtime
// is one service call on a thread of its own. Set as the process's transport when this library loads.
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <atomic>
#include <chrono>
#include <future>
#include <thread>

#include "apex/EvaluateCandidate.h"
#include "apex/ros/node_handles.hpp"
#include "apex_nodes/remote_workers.hpp"

namespace apex_nodes {
namespace {

using tuning::CandidateValues;
using tuning::RemoteOutcome;

/** An Optimizer served at ~<name>/evaluate until dropped. */
class Served {
 public:
  Served(const apex::Node& node, tuning::RemoteWorkers::Serve serve)
      : nh_(apex::privateNodeHandle(node)), serve_(std::move(serve)), spinner_(4, &queue_) {
    nh_.setCallbackQueue(&queue_);
    server_ = nh_.advertiseService("evaluate", &Served::evaluate, this);
    spinner_.start();
  }
  ~Served() {
    closing_ = true;  // a call under way answers now
    server_.shutdown();
    spinner_.stop();
  }

 private:
  bool evaluate(apex::EvaluateCandidate::Request& req, apex::EvaluateCandidate::Response& res) {
    CandidateValues values;
    for (std::size_t i = 0; i < req.dimensions.size() && i < req.values.size(); ++i)
      values.emplace_back(req.dimensions[i], req.values[i]);
    auto answer = std::make_shared<std::promise<RemoteOutcome>>();
    auto once = std::make_shared<std::atomic<bool>>(false);
    std::future<RemoteOutcome> future = answer->get_future();
    serve_(std::move(values), req.with_cost, [answer, once](RemoteOutcome o) {
      if (!once->exchange(true)) answer->set_value(std::move(o));
    });
    while (future.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready)
      if (closing_ || !ros::ok()) {
        res.error = "the runtime serving '" + nh_.getNamespace() + "' is shutting down";
        return true;
      }
    const RemoteOutcome o = future.get();
    res.error = o.error;
    res.fitness = o.fitness;
    res.ms_per_frame = o.ms_per_frame;
    return true;
  }

  ros::CallbackQueue queue_;
  ros::NodeHandle nh_;
  tuning::RemoteWorkers::Serve serve_;
  ros::AsyncSpinner spinner_;
  ros::ServiceServer server_;
  std::atomic<bool> closing_{false};
};

class RosRemoteWorkers : public tuning::RemoteWorkers {
 public:
  void evaluate(const std::string& runtime, const std::string& optimizer, CandidateValues values, bool with_cost,
                Done done) override {
    std::thread([service = ros::names::resolve(runtime) + "/" + optimizer + "/evaluate", values = std::move(values), with_cost,
                 done = std::move(done)] {
      done(call(service, values, with_cost));
    }).detach();  // owns all it uses; a call under way when the runtime stops ends with ROS
  }

  std::shared_ptr<void> serve(const apex::Node& node, Serve serve) override {
    if (!ros::isInitialized() || !dynamic_cast<const apex::RosHost*>(node.host())) return nullptr;
    return std::make_shared<Served>(node, std::move(serve));
  }

 private:
  static RemoteOutcome call(const std::string& service, const CandidateValues& values, bool with_cost) {
    if (!ros::service::waitForService(service, ros::Duration(10.0)))
      return {"no service " + service + " after 10 s: start a runtime there with the same graph", 0, 0};
    apex::EvaluateCandidate srv;
    for (const auto& [dimension, value] : values) {
      srv.request.dimensions.push_back(dimension);
      srv.request.values.push_back(value);
    }
    srv.request.with_cost = with_cost;
    if (!ros::service::call(service, srv)) return {"the call to " + service + " failed (did that runtime stop?)", 0, 0};
    if (!srv.response.error.empty()) return {service + ": " + srv.response.error, 0, 0};
    return {"", srv.response.fitness, srv.response.ms_per_frame};
  }
};

const bool kTransportSet = (tuning::setRemoteWorkers(std::make_shared<RosRemoteWorkers>()), true);

}  // namespace
}  // namespace apex_nodes
