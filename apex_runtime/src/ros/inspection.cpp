#include "inspection.hpp"

namespace apex {
namespace ros_host {

/** One inspected port. A port that carries any type advertises on its first message. */
struct Inspection::Tap {
  ros::NodeHandle nh;
  std::string topic;
  std::mutex mutex;
  Inspector inspector;
  ros::Publisher pub;

  void onMessage(const Message& m) {  // on the node's thread group
    if (m.isNothing() || m.isEndOfSequence()) return;  // no frame to show
    std::lock_guard<std::mutex> lock(mutex);
    if (!pub) {
      inspector = findInspector(m.type());
      pub = inspector.advertise(nh, topic);
    }
    if (pub.getNumSubscribers() == 0) return;
    inspector.publish(pub, m);
  }
};

Result<std::pair<std::string, std::string>> Inspection::set(Graph& graph, const std::string& node,
                                                             const std::string& port, bool enable) {
  const std::string key = node + "/" + port;
  std::lock_guard<std::mutex> lock(mutex_);
  if (!enable) {
    if (taps_.count(key)) (void)graph.setTap(node, port, nullptr);
    taps_.erase(key);
    return std::make_pair(std::string(), std::string());
  }
  if (auto it = taps_.find(key); it != taps_.end())
    return std::make_pair(it->second->pub ? it->second->pub.getTopic() : nh_.resolveName(it->second->topic),
                          it->second->inspector.message_type);
  auto iface = graph.nodeInterface(node);  // a subgraph's: its exports
  if (!iface && !findNode(graph.describe(), node)) return Status::error("no node named '" + node + "'");
  if (!iface) return Status::error("node '" + node + "' has a type unknown here: it has no ports to inspect");
  const TypeInfo* port_type = nullptr;
  if (auto* out = iface->findOutput(port)) port_type = out->type;
  if (auto* p = iface->findParam(port)) port_type = p->portType();
  auto tap = std::make_shared<Tap>();
  tap->nh = nh_;
  tap->topic = "inspect/" + node + "/" + port;
  if (port_type && port_type != typeOf<Any>()) {
    tap->inspector = findInspector(port_type);
    tap->pub = tap->inspector.advertise(nh_, tap->topic);
  } else {
    tap->inspector.message_type = "";  // decided by the first message
  }
  auto st = graph.setTap(node, port, [tap](const Message& m) { tap->onMessage(m); });
  if (!st) return st;
  taps_[key] = tap;
  return std::make_pair(nh_.resolveName(tap->topic), tap->inspector.message_type);
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
