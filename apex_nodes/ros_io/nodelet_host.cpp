// NodeletHost and NodeletSource: any nodelet plugin (image_proc/rectify, pcl/VoxelGrid, a lab's
// own) as a node of the graph, loaded by pluginlib as a nodelet manager loads it, under the
// runtime's private namespace (/apex/nodelets/<node>), its listed topics remapped under that name.
// NodeletHost answers frames: each frame's inputs are published to the nodelet and its answers
// (stamped as the frame) are the node's outputs, within `timeout`; it spins the nodelet's queue
// itself in process(), no thread. NodeletSource is a driven source: the nodelet publishes on its
// own (from topics of the ROS graph, several outputs per input or none) on a thread of the node.
// Two types, not a `mode` parameter: a parameter may change a node's ports but not how it is
// scheduled (graph_interface.cpp), and a source has no inputs to wait for.
#include <ros/ros.h>

#include <algorithm>
#include <map>
#include <memory>
#include <sstream>

#include "apex/core/registry.hpp"
#include "apex/ros/node_handles.hpp"
#include "nodelet_host.hpp"
#include "nodelet_reconfigure.hpp"

namespace apex_nodes {
namespace param = apex::param;
using nodelet_host::HostedNodelet;
using Texts = std::vector<std::string>;

/** What both types share: the parameters, loading, and the ports the topics make. */
class NodeletNode : public apex::Node {
 public:
  static inline const apex::ParamDecl<std::string> kNodelet =
      param::text("nodelet").init("image_proc/rectify").describe("the plugin, as `nodelet load` names it; a change reloads it");
  static inline const apex::ParamDecl<Texts> kOutputs =
      param::textList("outputs")
          .init({"image_rect:sensor_msgs/Image"})
          .describe("topics the nodelet advertises, topic:type, one output each (left/image: output left_image)")
          .shapesInterface();
  static inline const apex::ParamDecl<std::string> kConfig = param::text("config").describe(
      "its private parameters, a YAML map set before it loads (its dynamic_reconfigure server and param() read "
      "them), e.g. {leaf_size: 0.05}; a change reloads it. What it offers through dynamic_reconfigure becomes "
      "parameters of this node: their values win over these, except when this changes");
  static inline const apex::ParamDecl<Texts> kReconfigure =
      param::textList("reconfigure")
          .describe(
              "what the nodelet offers through dynamic_reconfigure, one YAML entry per parameter: filled in by "
              "this node when the nodelet loads (each becomes a parameter of this node, set live)")
          .shapesInterface();

  void setup() override {
    started_ = true;
    load(false);
  }
  void parameterChanged(const std::string& name) override {
    if (!started_ || name == "timeout" || name == kReconfigure.name()) return;  // before setup(): it loads once with every value
    if (auto o = offered(name)) {
      const auto now = nodelet_values_.find(name);
      if (now != nodelet_values_.end() && now->second == paramValue(name)) return;  // the nodelet has it (taken from it)
      nodelet_host::reconfigure(nodelet(), *o, paramValue(name), kAnswerWithin);
      nodelet_values_[name] = paramValue(name);
      return;
    }
    load(name == kConfig.name());  // a new config: the user's values, over the ones offered before
  }

 protected:
  /** Ports for `what`'s topics (inputs or outputs); an error refuses the parameter. */
  static apex::Status addPorts(const apex::ParamValues& p, const std::string& what, std::vector<apex::PortSpec>& ports) {
    auto topics = nodelet_host::parsePorts(p.get<Texts>(what), what);
    if (!topics) return topics.status();
    ports.clear();
    for (const auto& t : *topics)
      ports.push_back({t.port, t.type->port, false, "the nodelet's " + t.topic + " (" + t.type->name + ")"});
    return apex::Status::ok();
  }
  /** The offered parameters (`reconfigure`) on top of the ports `shape` makes. */
  static apex::InterfaceFn withOffered(apex::InterfaceFn shape) {
    return [shape](const apex::ParamValues& p, apex::Manifest& m) {
      if (auto st = shape(p, m); !st) return st;
      return nodelet_host::addOffered(p.get<Texts>(kReconfigure.name()), m);
    };
  }
  /** The manifest with the ports its default parameters make (what the palette shows). */
  static apex::Manifest withDefaultPorts(apex::Manifest m, const apex::InterfaceFn& shape) {
    apex::ParamValues defaults;
    for (const auto& spec : m.params) defaults.set(spec.name, spec.default_value);
    if (auto st = shape(defaults, m); !st) throw std::logic_error("NodeletHost's default ports: " + st.message());
    return m.shapedBy(withOffered(shape));
  }

  /** The nodelet, or the reason it is not loaded (thrown: the node's error, Nothing out). */
  HostedNodelet& nodelet() {
    if (!nodelet_) throw std::runtime_error(error_);
    return *nodelet_;
  }
  /** After a load: a source starts its thread. */
  virtual void loaded(HostedNodelet&) {}

 private:
  /** `config_wins`: its values go over the offered parameters' (else the other way round). */
  void load(bool config_wins) {
    nodelet_.reset();  // first: unloaded before the new one takes its name
    error_.clear();
    nodelet_values_.clear();
    try {
      if (!ros::isInitialized()) throw std::runtime_error("ROS is not initialised: a nodelet needs a ROS node");
      nodelet_ = std::make_unique<HostedNodelet>(options(config_wins));
      loaded(*nodelet_);
    } catch (const std::exception& e) {
      nodelet_.reset();
      error_ = e.what();
      throw;
    }
    try {  // what it offers: a failure here leaves the nodelet running, the parameters as they were
      takeOffers(nodelet_host::offeredBy(*nodelet_, kAnswerWithin));
    } catch (const std::exception& e) {
      reportError(e.what());
    }
  }
  /** What the loaded nodelet offers, and the values it has, become this node's: edits, applied
   *  after this call (Node::requestEdit), the list first. */
  void takeOffers(const nodelet_host::Offers& offers) {
    if (offers.entries != param<Texts>(kReconfigure.name())) requestEdit(kReconfigure.name(), offers.entries);
    auto offered = nodelet_host::parseOffered(offers.entries);
    if (!offered) throw std::runtime_error(nodelet_->describe() + ": " + offered.message());
    for (const auto& o : *offered) {
      const auto at = offers.values.find(o.name);
      const auto value = nodelet_host::valueOf(o, at == offers.values.end() ? std::string() : at->second);
      if (!value) continue;  // one the parameter cannot hold: the next set goes to the nodelet in any case
      nodelet_values_[o.param] = *value;
      // applied after the list (requests keep their order), so also to a parameter made by it
      const bool has = interface().findParam(o.param);
      if (!has || !(paramValue(o.param) == *value)) requestEdit(o.param, *value);
    }
  }
  nodelet_host::LoadOptions options(bool config_wins) const {
    nodelet_host::LoadOptions o;
    o.type = param<std::string>(kNodelet.name());
    if (o.type.empty()) throw std::invalid_argument("nodelet: name the plugin to load, e.g. image_proc/rectify");
    o.name = ros::names::append(runtimeNamespace(), "nodelets/" + name());
    if (interface().findParam("inputs")) o.inputs = topics("inputs");
    o.outputs = topics(kOutputs.name());
    const auto config = nodelet_host::parseConfig(param<std::string>(kConfig.name()));
    for (const auto& offer : offers())  // the values of its offered parameters, as last set here
      if (interface().findParam(offer.param)) o.config[offer.name] = nodelet_host::toNodelet(offer, paramValue(offer.param));
    for (const auto& [key, value] : config)
      if (config_wins || !o.config.count(key)) o.config[key] = value;
    const ros::NodeHandle nh = apex::nodeHandle(*this);
    o.remappings = nodelet_host::parseRemaps(param<Texts>("remap"), [&](const std::string& to) { return nh.resolveName(to); });
    return o;
  }
  std::vector<nodelet_host::PortTopic> topics(const std::string& what) const {
    auto parsed = nodelet_host::parsePorts(param<Texts>(what), what);
    if (!parsed) throw std::invalid_argument(parsed.message());
    return *parsed;
  }
  /** The runtime's private namespace (/apex); without a runtime, this process's node's. */
  std::string runtimeNamespace() const {
    if (const auto* ros_host = dynamic_cast<const apex::RosHost*>(host())) return ros_host->privateNodeHandle().getNamespace();
    return ros::this_node::getName();
  }

  /** The offered parameters this node has now. */
  std::vector<nodelet_host::Offered> offers() const {
    auto parsed = nodelet_host::parseOffered(param<Texts>(kReconfigure.name()));
    if (!parsed) throw std::invalid_argument(parsed.message());
    return *parsed;
  }
  std::optional<nodelet_host::Offered> offered(const std::string& param) const {
    for (auto& o : offers())
      if (o.param == param) return o;
    return std::nullopt;
  }

  static constexpr double kAnswerWithin = 5.0;  // seconds for its dynamic_reconfigure server to answer
  std::unique_ptr<HostedNodelet> nodelet_;  // its destructor unloads it
  std::map<std::string, apex::ParamValue> nodelet_values_;  // the offered parameters' values the nodelet has
  std::string error_;  // why it is not loaded
  bool started_ = false;
};

class NodeletHost : public NodeletNode {
 public:
  static inline const apex::ParamDecl<Texts> kInputs =
      param::textList("inputs")
          .init({"image_mono:sensor_msgs/Image", "camera_info:sensor_msgs/CameraInfo"})
          .describe("topics the nodelet subscribes to, topic:type, one input each; types: " + nodelet_host::rosTypeNames())
          .shapesInterface();
  static inline const apex::ParamDecl<double> kTimeout =
      param::number("timeout")
          .range(0.001, 60.0)
          .step(0.001)
          .init(1.0)
          .describe("seconds to wait for every output of a frame; after it the node sends Nothing and says which is missing");
  static inline const apex::ParamDecl<Texts> kRemap = param::textList("remap").describe(
      "its other topics, from:=to as `nodelet load` takes them (to: in the runtime's namespace)");
  static apex::Manifest manifest() {
    return withDefaultPorts(apex::Manifest("Runs a nodelet plugin on each frame: the inputs are published to it, its "
                                           "answers stamped as the frame are the outputs (image_proc/rectify, pcl/VoxelGrid...)")
                                .inCategory("ROS I/O")
                                .param(kNodelet)
                                .param(kInputs)
                                .param(kOutputs)
                                .param(kTimeout)
                                .param(kConfig)
                                .param(kRemap)
                                .param(kReconfigure),
                            shape);
  }

  void process() override {
    HostedNodelet& n = nodelet();
    const apex::Manifest& iface = interface();
    const auto deadline = ros::WallTime::now() + ros::WallDuration(timeout_.get());
    n.spin();  // what waits there: a lazy nodelet subscribes to its inputs once its outputs are read
    if (!spinUntil(n, deadline, [&] { return n.unsubscribedInputs().empty(); }))
      throw std::runtime_error(n.describe() + " did not subscribe to " + join(n.unsubscribedInputs()) + " within " + seconds() +
                               "; " + n.topics());
    std::vector<apex::Message> frame;
    for (const auto& in : iface.inputs) frame.push_back(inputMessage(in.name));
    n.send(frame);
    if (!spinUntil(n, deadline, [&] { return n.allArrived(); }))
      throw std::runtime_error(n.describe() + " did not answer within " + seconds() + ": " + n.missing());
    for (std::size_t o = 0; o < iface.outputs.size(); ++o) {
      auto r = n.take(o);
      if (!r.error.empty()) throw std::runtime_error(n.describe() + ": output '" + iface.outputs[o].name + "': " + r.error);
      publishMessage(iface.outputs[o].name, r.message);
    }
  }

 private:
  static apex::Status shape(const apex::ParamValues& p, apex::Manifest& m) {
    if (auto st = addPorts(p, kInputs.name(), m.inputs); !st) return st;
    if (auto st = addPorts(p, kOutputs.name(), m.outputs); !st) return st;
    for (const auto& in : p.get<Texts>(kInputs.name()))
      for (const auto& out : p.get<Texts>(kOutputs.name()))
        if (in.substr(0, in.rfind(':')) == out.substr(0, out.rfind(':')))
          return apex::Status::error("'" + in.substr(0, in.rfind(':')) + "' is both an input and an output of the nodelet");
    return apex::Status::ok();
  }
  /** Spins the nodelet's queue until `done` or `deadline`; false at the deadline. */
  template <class Done>
  static bool spinUntil(HostedNodelet& n, const ros::WallTime& deadline, Done done) {
    return n.spinUntil(done, std::max(0.0, (deadline - ros::WallTime::now()).toSec()));
  }
  static std::string join(const Texts& texts) {
    std::string out;
    for (const auto& t : texts) out += (out.empty() ? "'" : ", '") + t + "'";
    return out;
  }
  std::string seconds() const {
    std::ostringstream s;
    s << timeout_.get() << " s";
    return s.str();
  }

  void loaded(HostedNodelet& n) override { n.spin(); }  // a lazy nodelet subscribes now, not at the first frame

  apex::Param<double> timeout_{this, kTimeout};
};

class NodeletSource : public NodeletNode {
 public:
  static inline const apex::ParamDecl<Texts> kRemap =
      param::textList("remap")
          .init({"image_mono:=camera/image_raw"})
          .describe("the topics it reads, from:=to as `nodelet load` takes them (to: in the runtime's namespace)");
  static apex::Manifest manifest() {
    return withDefaultPorts(
        apex::Manifest("Runs a nodelet plugin that publishes on its own (fed by ROS topics, any number "
                       "of outputs per input): each firing sends the newest message of each output")
            .inCategory("ROS I/O")
            .param(kNodelet)
            .param(kOutputs)
            .param(kConfig)
            .param(kRemap)
            .param(kReconfigure)
            .driven(),
        [](const apex::ParamValues& p, apex::Manifest& m) { return addPorts(p, kOutputs.name(), m.outputs); });
  }

  void process() override {
    HostedNodelet& n = nodelet();
    const apex::Manifest& iface = interface();
    for (std::size_t o = 0; o < iface.outputs.size(); ++o) {
      auto r = n.take(o);  // nothing new on a topic: Nothing on its output
      if (!r.error.empty()) reportError(n.describe() + ": output '" + iface.outputs[o].name + "': " + r.error);
      if (r.arrived) publishMessage(iface.outputs[o].name, r.message);
    }
  }

 private:
  void loaded(HostedNodelet& n) override {
    n.spinInThread([this] { notifyNewData(); });
  }
};

}  // namespace apex_nodes

APEX_REGISTER_NODE(apex_nodes::NodeletHost, "apex_nodes/NodeletHost");
APEX_REGISTER_NODE(apex_nodes::NodeletSource, "apex_nodes/NodeletSource");
