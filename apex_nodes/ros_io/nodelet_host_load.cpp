// Loading and unloading a hosted nodelet: one pluginlib loader for the process (as a nodelet
// manager keeps one), unique names, the nodelet's private parameters, its topics remapped under
// its name, and teardown in the order a manager uses.
#include <nodelet/nodelet.h>
#include <pluginlib/class_loader.hpp>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <set>
#include <stdexcept>

#include "apex/core/registry.hpp"
#include "nodelet_host.hpp"

namespace apex_nodes {
namespace nodelet_host {
namespace {

using Loader = pluginlib::ClassLoader<nodelet::Nodelet>;

/** The process's loader and the names in use, behind one lock: plugins are made and destroyed
 *  under it. The loader is never destroyed (as a manager's lives as long as its process): a
 *  library it loaded stays loaded, so no code of a nodelet is unmapped while anything of it may
 *  still run, and a second load of a plugin costs nothing. */
struct Plugins {
  std::mutex m;
  std::unique_ptr<Loader> loader;  // made on first use: it reads every package's plugin list
  std::set<std::string> names;

  Loader& get() {
    if (!loader) loader = std::make_unique<Loader>("nodelet", "nodelet::Nodelet");
    return *loader;
  }
};

Plugins& plugins() {
  static Plugins* p = new Plugins;  // never destroyed, see above
  return *p;
}

std::string notDeclared(const std::string& type, Loader& loader) {
  const auto declared = loader.getDeclaredClasses();
  std::string near;
  for (const auto& name : apex::closestNames(type, declared, 5)) near += (near.empty() ? "" : ", ") + name;
  return "no nodelet plugin '" + type + "' is declared (" + std::to_string(declared.size()) +
         " are: rospack plugins --attrib=plugin nodelet)" + (near.empty() ? "" : ": did you mean " + near + "?");
}

boost::shared_ptr<nodelet::Nodelet> create(const std::string& type) {
  Loader& loader = plugins().get();
  if (!loader.isClassAvailable(type)) loader.refreshDeclaredClasses();  // installed since: as a manager does
  if (!loader.isClassAvailable(type)) throw std::runtime_error(notDeclared(type, loader));
  try {
    return loader.createInstance(type);
  } catch (const pluginlib::PluginlibException& e) {
    throw std::runtime_error("nodelet plugin '" + type + "' (package " + loader.getClassPackage(type) +
                             ") cannot be made: " + e.what() +
                             " (pluginlib looks for the library in <prefix>/lib of each CMAKE_PREFIX_PATH entry and in "
                             "/usr/lib/<arch>)");
  }
}

std::string stampText(const ros::Time& t) {
  std::string nsec = std::to_string(t.nsec);
  return std::to_string(t.sec) + "." + std::string(9 - nsec.size(), '0') + nsec;
}

std::string uniqueName(const std::string& wanted) {
  std::string name = wanted;
  for (int i = 2; !plugins().names.insert(name).second; ++i) name = wanted + "_" + std::to_string(i);
  return name;
}

XmlRpc::XmlRpcValue toXmlRpc(const YAML::Node& node, const std::string& key) {
  XmlRpc::XmlRpcValue v;
  if (node.IsMap()) {
    for (const auto& kv : node) v[kv.first.as<std::string>()] = toXmlRpc(kv.second, key + "/" + kv.first.as<std::string>());
  } else if (node.IsSequence()) {
    v.setSize(static_cast<int>(node.size()));
    for (std::size_t i = 0; i < node.size(); ++i) v[static_cast<int>(i)] = toXmlRpc(node[i], key);
  } else if (!node.IsScalar()) {
    throw std::invalid_argument("config: '" + key + "' has no value");
  } else if (node.Tag() == "!") {  // quoted: a string, whatever it looks like
    v = node.as<std::string>();
  } else if (int i; YAML::convert<int>::decode(node, i)) {
    v = i;
  } else if (double d; YAML::convert<double>::decode(node, d)) {
    v = d;
  } else if (bool b; YAML::convert<bool>::decode(node, b)) {
    v = b;
  } else {
    v = node.as<std::string>();
  }
  return v;
}

}  // namespace

std::map<std::string, XmlRpc::XmlRpcValue> parseConfig(const std::string& yaml) {
  std::map<std::string, XmlRpc::XmlRpcValue> out;
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument("config: not YAML: " + std::string(e.what()));
  }
  if (root.IsNull()) return out;
  if (!root.IsMap()) throw std::invalid_argument("config: not a YAML map of parameters, e.g. {leaf_size: 0.05}");
  for (const auto& kv : root) {
    const auto key = kv.first.as<std::string>();
    std::string why;
    if (!ros::names::validate(key, why) || key.empty() || key.front() == '/' || key.front() == '~')
      throw std::invalid_argument("config: '" + key + "' is not a relative parameter name" + (why.empty() ? "" : ": " + why));
    out[key] = toXmlRpc(kv.second, key);
  }
  return out;
}

std::map<std::string, std::string> parseRemaps(const std::vector<std::string>& entries,
                                               const std::function<std::string(const std::string&)>& resolve) {
  std::map<std::string, std::string> out;
  for (const auto& e : entries) {
    const auto at = e.find(":=");
    if (at == std::string::npos || at == 0 || at + 2 == e.size())
      throw std::invalid_argument("remap: '" + e + "' is not from:=to (e.g. input:=/camera/points)");
    try {
      out[e.substr(0, at)] = resolve(e.substr(at + 2));
    } catch (const ros::Exception& x) {
      throw std::invalid_argument("remap: '" + e + "': " + x.what());
    }
  }
  return out;
}

HostedNodelet::HostedNodelet(LoadOptions options) : options_(std::move(options)) {
  {
    std::lock_guard<std::mutex> lock(plugins().m);
    name_ = uniqueName(options_.name);
  }
  try {
    load();
  } catch (const std::exception& e) {
    // Made: its onInit() failed, named here; else the error of making it, which names the plugin.
    const std::string why = nodelet_ ? describe() + ": " + e.what() : std::string(e.what());
    unload();
    throw std::runtime_error(why);
  }
}

HostedNodelet::~HostedNodelet() { unload(); }

void HostedNodelet::load() {
  ros::param::del(name_);  // what a nodelet of this name left (its dynamic_reconfigure values)
  for (const auto& [key, value] : options_.config) ros::param::set(name_ + "/" + key, value);
  ros::NodeHandle nh = handle();
  received_.resize(options_.outputs.size());
  late_.resize(options_.outputs.size());
  advertiseInputs(nh);
  subscribeOutputs(nh);
  std::map<std::string, std::string> remaps = options_.remappings;  // ports win over `remap`
  for (const auto* side : {&options_.inputs, &options_.outputs})
    for (const auto& p : *side) remaps[p.topic] = ros::names::append(name_, p.topic);
  std::lock_guard<std::mutex> lock(plugins().m);
  nodelet_ = create(options_.type);
  nodelet_->init(name_, remaps, {}, &queue_, &queue_);  // its onInit(): subscribes, advertises
}

void HostedNodelet::unload() {
  stopSpinning();
  queue_.disable();  // nothing more waits in it...
  for (auto& p : inputs_) p.shutdown();
  for (auto& s : outputs_) s.shutdown();
  queue_.clear();
  std::unique_lock<std::mutex> lock(plugins().m);
  nodelet_.reset();  // ...while the nodelet goes: its handles shut its topics, services and timers down
  queue_.clear();
  if (aside_.joinable()) {  // a call to its services returns once they are gone (no other load waits meanwhile)
    lock.unlock();
    aside_.join();
    lock.lock();
  }
  if (name_.empty()) return;
  if (ros::isStarted() && !ros::isShuttingDown()) ros::param::del(name_);
  plugins().names.erase(name_);
  name_.clear();
}

std::string HostedNodelet::describe() const { return "nodelet '" + options_.type + "' (" + name_ + ")"; }

void HostedNodelet::advertiseInputs(ros::NodeHandle& nh) {
  for (const auto& p : options_.inputs) inputs_.push_back(p.type->advertise(nh, ros::names::append(name_, p.topic)));
}

void HostedNodelet::subscribeOutputs(ros::NodeHandle& nh) {
  for (std::size_t i = 0; i < options_.outputs.size(); ++i) {
    const auto& p = options_.outputs[i];
    outputs_.push_back(
        p.type->subscribe(nh, ros::names::append(name_, p.topic), [this, i](Received r) { store(i, std::move(r)); }));
  }
}

void HostedNodelet::spinInThread(std::function<void()> arrived) {
  {
    std::lock_guard<std::mutex> lock(m_);
    arrived_ = std::move(arrived);
  }
  spinning_ = true;
  spinner_ = std::thread([this] {
    while (spinning_) queue_.callAvailable(ros::WallDuration(0.1));
  });
}

void HostedNodelet::stopSpinning() {
  spinning_ = false;
  queue_.disable();  // wakes the spinner's wait
  if (spinner_.joinable()) spinner_.join();
  queue_.enable();
}

void HostedNodelet::spin(double timeout) { queue_.callAvailable(ros::WallDuration(timeout)); }

bool HostedNodelet::spinUntil(const std::function<bool()>& done, double timeout) {
  const auto deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  while (!done()) {
    const double left = (deadline - ros::WallTime::now()).toSec();
    if (left <= 0) return false;
    if (spinning_) std::this_thread::sleep_for(std::chrono::milliseconds(2));  // its thread runs the callbacks
    else spin(std::min(left, 0.01));
  }
  return true;
}

bool HostedNodelet::callAside(std::function<void()> call, double timeout) {
  if (aside_.joinable()) {
    if (!aside_done_->load())
      throw std::runtime_error(describe() +
                               " has still not answered an earlier call that timed out: not called again until it does");
    aside_.join();
  }
  auto done = std::make_shared<std::atomic<bool>>(false);
  aside_done_ = done;
  aside_ = std::thread([call = std::move(call), done] {
    call();
    done->store(true);
  });
  return spinUntil([&] { return done->load(); }, timeout);
}

ros::NodeHandle HostedNodelet::handle() {
  ros::NodeHandle nh;
  nh.setCallbackQueue(&queue_);
  return nh;
}

std::vector<std::string> HostedNodelet::unsubscribedInputs() const {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < inputs_.size(); ++i)
    if (inputs_[i].getNumSubscribers() == 0) out.push_back(options_.inputs[i].topic);
  return out;
}

void HostedNodelet::store(std::size_t output, Received r) {
  std::function<void()> arrived;
  {
    std::lock_guard<std::mutex> lock(m_);
    if (expected_ && r.stamp != *expected_) {
      late_[output] = r.stamp;  // an answer to an earlier frame
      return;
    }
    received_[output] = std::move(r);
    arrived = arrived_;
  }
  if (arrived) arrived();
}

void HostedNodelet::send(const std::vector<apex::Message>& inputs) {
  std::optional<ros::Time> stamp;
  for (std::size_t i = 0; i < inputs.size() && !stamp; ++i) stamp = options_.inputs.at(i).type->stamp(inputs[i]);
  {
    std::lock_guard<std::mutex> lock(m_);
    expected_ = stamp;
    for (auto& r : received_) r = Received();
    for (auto& l : late_) l.reset();
  }
  for (std::size_t i = 0; i < inputs.size(); ++i) options_.inputs.at(i).type->publish(inputs_.at(i), inputs[i]);
}

Received HostedNodelet::take(std::size_t output) {
  std::lock_guard<std::mutex> lock(m_);
  return std::exchange(received_.at(output), Received());
}

bool HostedNodelet::allArrived() const {
  std::lock_guard<std::mutex> lock(m_);
  return std::all_of(received_.begin(), received_.end(), [](const Received& r) { return r.arrived; });
}

std::string HostedNodelet::missing() const {
  std::string out;
  std::lock_guard<std::mutex> lock(m_);
  for (std::size_t i = 0; i < received_.size(); ++i) {
    if (received_[i].arrived) continue;
    out += (out.empty() ? "" : "; ") + std::string("no '") + options_.outputs[i].topic + "'";
    if (late_[i]) out += " stamped " + stampText(*expected_) + " (one stamped " + stampText(*late_[i]) + " came)";
  }
  return out + "; " + topics();
}

std::string HostedNodelet::topics() const {
  // Its topics: under its name (remapped, or private), or beside it (public, not remapped).
  const std::string mine = name_ + "/", parent = ros::names::parentNamespace(name_) + "/";
  auto list = [&](const ros::V_string& topics, const std::vector<PortTopic>& ours) {
    std::string out;
    for (const auto& t : topics) {
      const bool under = t.rfind(mine, 0) == 0;
      const bool beside = t.rfind(parent, 0) == 0 && t.find('/', parent.size()) == std::string::npos;
      const bool own =
          std::any_of(ours.begin(), ours.end(), [&](const PortTopic& p) { return ros::names::append(name_, p.topic) == t; });
      if ((under || beside) && !own) out += (out.empty() ? "" : ", ") + t;
    }
    return out.empty() ? std::string("none") : out;
  };
  ros::V_string subscribed, advertised;
  ros::this_node::getSubscribedTopics(subscribed);
  ros::this_node::getAdvertisedTopics(advertised);
  return "it advertises " + list(advertised, options_.inputs) + " and subscribes to " + list(subscribed, options_.outputs);
}

}  // namespace nodelet_host
}  // namespace apex_nodes
