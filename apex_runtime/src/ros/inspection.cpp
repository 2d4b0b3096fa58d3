#include "inspection.hpp"

#include <chrono>

#include <std_msgs/String.h>

#include "apex/core/node_names.hpp"

namespace apex {
namespace ros_host {

/** One inspected port, published whole on inspect/<node>/<port> and, for the panel's
 *  previews, at most kPreviewRate times a second and shrunk on preview/<node>/<port>, with
 *  what the message was (its inspector's describe, e.g. an image's real size) on
 *  preview/<node>/<port>/about. A port that carries any type, or ROS messages of any type,
 *  advertises on its first message. */
struct Inspection::Tap {
  struct Topic {
    bool wanted = false;
    std::string name;
    ros::Publisher pub;
  };
  ros::NodeHandle nh;
  std::mutex mutex;
  Inspector inspector;
  bool typed = false;  // inspector known (from the port's type, or the first message)
  Topic whole, preview, about;
  std::chrono::steady_clock::time_point next_preview{};
  /** A subscriber connected: a held frame is sent again for it (Inspection::watchedAnew). */
  std::function<void()> watched;

  /** Under mutex, once the inspector is known; `first`: the message being sent, if any (a type
   *  whose ROS type is its message's own is advertised at its first message). */
  void advertise(const Message* first = nullptr) {
    const ros::SubscriberStatusCallback connected = [w = watched](const ros::SingleSubscriberPublisher&) {
      if (w) w();
    };
    for (Topic* t : {&whole, &preview}) {
      if (!t->wanted || t->pub) continue;
      if (!inspector.advertise_as) t->pub = inspector.advertise(nh, t->name, connected);
      else if (first) t->pub = inspector.advertise_as(nh, t->name, *first, connected);
    }
    if (preview.wanted && inspector.describe && !about.pub) about.pub = nh.advertise<std_msgs::String>(about.name, 1);
  }

  void onMessage(const Message& m) {  // on the node's thread group
    if (m.isNothing() || m.isEndOfSequence()) return;  // no frame to show
    std::lock_guard<std::mutex> lock(mutex);
    if (!typed) inspector = findInspector(m.type()), typed = true;
    advertise(&m);
    if (whole.pub && whole.pub.getNumSubscribers() > 0) inspector.publish(whole.pub, m);
    if (!preview.pub || preview.pub.getNumSubscribers() == 0) return;
    const auto now = std::chrono::steady_clock::now();
    if (now < next_preview) return;  // throttled: the graph pays a clock read
    next_preview = now + std::chrono::milliseconds(1000 / kPreviewRate);
    inspector.publish(preview.pub, inspector.shrink ? inspector.shrink(m, kPreviewWidth) : m);
    if (about.pub && about.pub.getNumSubscribers() > 0) {
      std_msgs::String text;
      text.data = inspector.describe(m);
      about.pub.publish(text);
    }
  }
};

Result<std::pair<std::string, std::string>> Inspection::set(Graph& graph, const std::string& node, const std::string& port,
                                                            bool enable, bool preview) {
  const std::string key = node + "/" + port;
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = taps_.find(key);
  if (!enable) {
    if (it == taps_.end()) {  // nothing to stop: still, a node or port that is not there is named
      auto iface = graph.nodeInterface(node);
      if (!iface && !findNode(graph.describe(), node)) return Status::error("no node named '" + node + "'");
      if (iface && !iface->findOutput(port) && !iface->findParam(port))
        return Status::error(nodeLabel(node) + " has no output or parameter '" + port + "'");
      return std::make_pair(std::string(), std::string());
    }
    {
      std::lock_guard<std::mutex> tap_lock(it->second->mutex);
      Tap::Topic& t = preview ? it->second->preview : it->second->whole;
      t.wanted = false, t.pub = ros::Publisher();
      if (preview) it->second->about.pub = ros::Publisher();
      if (it->second->whole.wanted || it->second->preview.wanted) return std::make_pair(std::string(), std::string());
    }
    (void)graph.setTap(node, port, nullptr);
    taps_.erase(it);
    return std::make_pair(std::string(), std::string());
  }
  std::shared_ptr<Tap> tap;
  if (it != taps_.end()) {
    tap = it->second;
  } else {
    auto iface = graph.nodeInterface(node);  // a subgraph's: its exports
    if (!iface && !findNode(graph.describe(), node)) return Status::error("no node named '" + node + "'");
    if (!iface) return Status::error(nodeLabel(node) + " has a type unknown here: it has no ports to inspect");
    const TypeInfo* port_type = nullptr;
    if (auto* out = iface->findOutput(port)) port_type = out->type;
    if (auto* p = iface->findParam(port)) port_type = p->portType();
    tap = std::make_shared<Tap>();
    tap->nh = nh_;
    tap->watched = [this, &graph, key, node, port, weak = std::weak_ptr<Tap>(tap)] { watchedAnew(graph, key, node, port, weak); };
    tap->whole.name = "inspect/" + key;
    tap->preview.name = "preview/" + key;
    tap->about.name = "preview/" + key + "/about";
    if (port_type && port_type != typeOf<Any>()) tap->inspector = findInspector(port_type), tap->typed = true;
    auto st = graph.setTap(node, port, [tap](const Message& m) { tap->onMessage(m); });
    if (!st) return st;
    taps_[key] = tap;
  }
  std::lock_guard<std::mutex> tap_lock(tap->mutex);
  Tap::Topic& t = preview ? tap->preview : tap->whole;
  t.wanted = true;
  if (tap->typed) tap->advertise();
  const bool type_known = tap->typed && !tap->inspector.advertise_as;  // else: the first message's
  return std::make_pair(t.pub ? t.pub.getTopic() : nh_.resolveName(t.name), type_known ? tap->inspector.message_type : "");
}

void Inspection::watchedAnew(Graph& graph, const std::string& key, const std::string& node, const std::string& port,
                             const std::weak_ptr<Tap>& weak) {
  const std::shared_ptr<Tap> tap = weak.lock();
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = taps_.find(key);
  if (!tap || it == taps_.end() || it->second != tap) return;  // ended, or another tap since
  (void)graph.setTap(node, port, [tap](const Message& m) { tap->onMessage(m); });  // a held frame: sent again
}

void Inspection::forgetNode(const std::string& node) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = taps_.begin(); it != taps_.end();) {
    it = it->first.rfind(node + "/", 0) == 0 ? taps_.erase(it) : std::next(it);
  }
}

void Inspection::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  taps_.clear();
}

}  // namespace ros_host
}  // namespace apex
