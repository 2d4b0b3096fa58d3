// A nodelet plugin (pluginlib, as a nodelet manager loads one) inside a node of the graph: its
// topics remapped under its own name, where the node publishes its inputs to it and reads its
// answers back, in this process (roscpp hands shared pointers over without serialising when the
// C++ types match). Its callbacks wait in one queue of its own that the node spins.
#pragma once

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <XmlRpcValue.h>

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "apex/core/message.hpp"
#include "apex/core/result.hpp"

namespace nodelet {
class Nodelet;
}

namespace apex_nodes {
namespace nodelet_host {

/** A message as it came back from the nodelet: converted to the port's type, or why not. */
struct Received {
  apex::Message message;
  ros::Time stamp;
  std::string error;  ///< the conversion failed (the message stays Nothing)
  bool arrived = false;
};

/** One ROS message type a port can carry, and how its messages go to the nodelet and come back. */
struct RosType {
  std::string name;  ///< "sensor_msgs/Image"
  const apex::TypeInfo* port;  ///< what the node's port carries
  std::function<ros::Publisher(ros::NodeHandle&, const std::string& topic)> advertise;
  std::function<void(const ros::Publisher&, const apex::Message&)> publish;
  std::function<ros::Subscriber(ros::NodeHandle&, const std::string& topic, std::function<void(Received)>)> subscribe;
  std::function<std::optional<ros::Time>(const apex::Message&)> stamp;  ///< its header's, if it has one
};

/** The type named `name` ("sensor_msgs/Image"), or nullptr. */
const RosType* findRosType(const std::string& name);
/** The names of the types ports can carry, for errors. */
std::string rosTypeNames();

/** A topic of the nodelet that is a port of the node. */
struct PortTopic {
  std::string topic;  ///< as the nodelet names it: "image_mono", "left/image_raw"
  std::string port;  ///< the port's name: the topic with '/' as '_'
  const RosType* type;
};
/** Parses `what`'s entries, "topic:type" each; an error names the entry and says why. */
apex::Result<std::vector<PortTopic>> parsePorts(const std::vector<std::string>& entries, const std::string& what);

/** What a nodelet is loaded with. */
struct LoadOptions {
  std::string type;  ///< its plugin's name, e.g. "image_proc/rectify"
  std::string name;  ///< wanted name (resolved); a suffix makes it unique in the process
  std::vector<PortTopic> inputs, outputs;
  std::map<std::string, std::string> remappings;  ///< more: from (as the nodelet names it) -> to (resolved)
  std::map<std::string, XmlRpc::XmlRpcValue> config;  ///< set as its private parameters before it loads
};

/** Parses a YAML map (`config`) into parameter values; empty text: none. Throws std::invalid_argument. */
std::map<std::string, XmlRpc::XmlRpcValue> parseConfig(const std::string& yaml);
/** Parses "from:=to" entries; `to` resolved by `resolve`. Throws std::invalid_argument. */
std::map<std::string, std::string> parseRemaps(const std::vector<std::string>& entries,
                                               const std::function<std::string(const std::string&)>& resolve);

/** A loaded nodelet. Not thread-safe: one thread uses it (a node's thread group), apart from
 *  the spinner thread of spinInThread(). Its destructor unloads it. */
class HostedNodelet {
 public:
  /** Loads it; throws std::runtime_error naming the plugin (and the closest declared ones when
   *  it is not declared) if it cannot be made or initialised. */
  explicit HostedNodelet(LoadOptions options);
  ~HostedNodelet();
  HostedNodelet(const HostedNodelet&) = delete;
  HostedNodelet& operator=(const HostedNodelet&) = delete;

  /** "nodelet 'image_proc/rectify' (/apex/nodelets/rectify)": for messages. */
  std::string describe() const;
  const std::string& name() const { return name_; }

  /** Spins its queue on a thread of its own (a source) until destroyed; `arrived` is called there
   *  after each output is stored. */
  void spinInThread(std::function<void()> arrived);
  /** Runs every callback waiting in its queue, waiting up to `timeout` for the first (no thread). */
  void spin(double timeout = 0.0);
  /** Until `done()` or `timeout` seconds: spins its queue, or waits while its own thread does
   *  (spinInThread). False at the timeout. */
  bool spinUntil(const std::function<bool()>& done, double timeout);
  /** Runs `call` on a thread of its own while this one spins the queue, for a call the nodelet
   *  answers through its queue (a service of its own): true when `call` returned within `timeout`.
   *  One at a time: while an earlier call has not returned (the nodelet never answered it),
   *  throws std::runtime_error saying so. The thread is joined at the latest when the nodelet
   *  unloads (its services go, so the call returns). */
  bool callAside(std::function<void()> call, double timeout);
  /** A handle whose callbacks run in its queue (with its own). */
  ros::NodeHandle handle();

  /** The inputs with no subscriber yet (the nodelet did not subscribe to them, or not yet). */
  std::vector<std::string> unsubscribedInputs() const;
  /** Publishes one frame to the nodelet, a message per input, and from then on stores only
   *  outputs stamped as the frame (the first input with a header): others are late answers,
   *  remembered for errors. Forgets the outputs received so far. */
  void send(const std::vector<apex::Message>& inputs);
  /** Takes what came on an output since the last take (arrived false: nothing). */
  Received take(std::size_t output);
  /** True when every output has something to take. */
  bool allArrived() const;
  /** Why the outputs that have not come did not: for a timeout's error. */
  std::string missing() const;
  /** The topics it advertises and subscribes to, under its name or beside it: for errors. */
  std::string topics() const;

 private:
  void load();
  void unload();  // safe on a half-made one, and twice
  void advertiseInputs(ros::NodeHandle& nh);
  void subscribeOutputs(ros::NodeHandle& nh);
  void store(std::size_t output, Received r);
  void stopSpinning();

  LoadOptions options_;
  std::string name_;
  ros::CallbackQueue queue_;  // the nodelet's callbacks (its ST and MT queue both) and ours
  boost::shared_ptr<nodelet::Nodelet> nodelet_;
  std::vector<ros::Publisher> inputs_;
  std::vector<ros::Subscriber> outputs_;
  mutable std::mutex m_;  // received_, expected_, late_, arrived_
  std::vector<Received> received_;
  std::vector<std::optional<ros::Time>> late_;
  std::optional<ros::Time> expected_;
  std::function<void()> arrived_;
  std::atomic<bool> spinning_{false};
  std::thread spinner_;
  std::shared_ptr<std::atomic<bool>> aside_done_;  // the call aside, while its thread lives
  std::thread aside_;
};

}  // namespace nodelet_host
}  // namespace apex_nodes
