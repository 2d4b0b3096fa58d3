#include "apex_rviz_plugin/rviz_displays.hpp"

#include <algorithm>

namespace apex_rviz_plugin {
namespace {

const apex::NodeInfo* findNode(const apex::GraphState& graph, const std::string& name) {
  for (const auto& n : graph.nodes)
    if (n.name == name) return &n;
  return nullptr;
}

/** A port that can be inspected: an output, or a parameter's port. */
bool hasInspectable(const apex::NodeInfo& node, const std::string& port) {
  return std::any_of(node.ports.begin(), node.ports.end(), [&](const apex::PortInfo& p) {
    return p.name == port && (p.kind == "output" || p.kind == "param_out" || p.kind == "param_in");
  });
}

/** Every input the node needs is linked: else it never runs and its ports publish nothing. */
bool runnable(const apex::NodeInfo& node, const apex::GraphState& graph) {
  return std::all_of(node.ports.begin(), node.ports.end(), [&](const apex::PortInfo& p) {
    if (p.kind != "input" || p.optional) return true;
    return std::any_of(graph.connections.begin(), graph.connections.end(),
                       [&](const apex::Connection& c) { return c.to_node == node.name && c.to_port == p.name; });
  });
}

}  // namespace

std::optional<RvizDisplay> rvizDisplayFor(const std::string& message_type) {
  static const std::map<std::string, RvizDisplay> kDisplays = {
      {"sensor_msgs/Image", {"rviz/Image", "Image Topic"}},
      {"sensor_msgs/PointCloud2", {"rviz/PointCloud2", "Topic"}},
      {"sensor_msgs/LaserScan", {"rviz/LaserScan", "Topic"}},
      {"nav_msgs/OccupancyGrid", {"rviz/Map", "Topic"}},
      {"visualization_msgs/MarkerArray", {"rviz/MarkerArray", "Marker Topic"}},
      {"visualization_msgs/Marker", {"rviz/Marker", "Marker Topic"}},
      {"geometry_msgs/PoseStamped", {"rviz/Pose", "Topic"}},
      {"geometry_msgs/PoseArray", {"rviz/PoseArray", "Topic"}},
      {"tf2_msgs/TFMessage", {"rviz/TF", ""}},  // rviz's TF display reads /tf itself
  };
  const auto it = kDisplays.find(message_type);
  if (it == kDisplays.end()) return std::nullopt;
  return it->second;
}

std::string noRvizDisplayReason(const std::string& message_type) {
  if (rvizDisplayFor(message_type)) return "";
  if (message_type.empty()) return "its ROS message type is known from its first message only";
  if (message_type == "geometry_msgs/TransformStamped")
    return "rviz shows transforms from /tf only (its TF display), not from a topic";
  return "rviz has no display for " + message_type;
}

std::string FollowedDisplays::displayName(const std::string& node, const std::string& port) {
  return "apex: " + node + "/" + port;
}

int FollowedDisplays::follow(const std::string& node, const std::string& port) {
  int id = find(node, port);
  if (id < 0) id = next_id_++, followed_[id] = Followed{node, port};
  followed_[id].inspected = true;
  return id;
}

int FollowedDisplays::find(const std::string& node, const std::string& port) const {
  for (const auto& [id, f] : followed_)
    if (f.node == node && f.port == port) return id;
  return -1;
}

bool FollowedDisplays::enabled(int id) const {
  const auto it = followed_.find(id);
  return it != followed_.end() && it->second.runnable && it->second.inspected;
}

void FollowedDisplays::forget(int id) { followed_.erase(id); }

void FollowedDisplays::expectRename(const std::string& from, const std::string& to) { renames_[from] = to; }

std::string FollowedDisplays::renamedPath(const std::string& node, const apex::GraphState& graph) const {
  for (const auto& [from, to] : renames_) {
    const bool inside = node.size() > from.size() && node.compare(0, from.size() + 1, from + "/") == 0;
    if ((node == from || inside) && findNode(graph, to) && !findNode(graph, from)) return to + node.substr(from.size());
  }
  return "";
}

std::vector<DisplayChange> FollowedDisplays::update(const apex::GraphState& graph) {
  using Kind = DisplayChange::Kind;
  std::vector<DisplayChange> out;
  for (auto it = followed_.begin(); it != followed_.end();) {
    const int id = it->first;
    Followed& f = it->second;
    const bool was = f.runnable && f.inspected;
    const apex::NodeInfo* node = findNode(graph, f.node);
    if (!node) {  // renamed as expected, or gone
      const std::string to = renamedPath(f.node, graph);
      if (!to.empty()) {
        f.node = to, f.inspected = false;  // the runtime forgets a renamed node's inspections
        out.push_back({Kind::kRename, id, f.node, f.port, displayName(f.node, f.port)});
        node = findNode(graph, to);
      }
    }
    if (!node || !hasInspectable(*node, f.port)) {
      out.push_back({Kind::kRemove, id, f.node, f.port, ""});
      it = followed_.erase(it);
      continue;
    }
    f.runnable = runnable(*node, graph);
    const bool now = f.runnable && f.inspected;
    const bool renamed = !out.empty() && out.back().kind == Kind::kRename && out.back().id == id;
    if (now != was && !renamed) out.push_back({now ? Kind::kEnable : Kind::kDisable, id, f.node, f.port, ""});
    ++it;
  }
  for (auto it = renames_.begin(); it != renames_.end();) {  // done, or refused (both names there)
    const bool settled = findNode(graph, it->second) != nullptr;
    it = settled ? renames_.erase(it) : std::next(it);
  }
  return out;
}

}  // namespace apex_rviz_plugin
