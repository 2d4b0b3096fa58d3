#include "apex_rviz_plugin/layout.hpp"

#include <graphviz/gvc.h>

#include <algorithm>
#include <limits>
#include <memory>

namespace apex_rviz_plugin {
namespace {

constexpr double kPointsPerInch = 72;  // graphviz's units; one scene unit is one point

void set(void* object, const char* key, const std::string& value) {
  agsafeset(object, const_cast<char*>(key), const_cast<char*>(value.c_str()), const_cast<char*>(""));
}

}  // namespace

std::map<std::string, std::pair<double, double>> layeredLayout(const std::map<std::string, Box>& boxes,
                                                               const std::vector<std::pair<std::string, std::string>>& edges,
                                                               double gap) {
  std::map<std::string, std::pair<double, double>> out;
  if (boxes.empty()) return out;
  agseterr(AGERR);  // warnings stay out of the console
  std::unique_ptr<GVC_t, int (*)(GVC_t*)> gvc(gvContext(), gvFreeContext);
  std::unique_ptr<Agraph_t, int (*)(Agraph_t*)> g(agopen(const_cast<char*>("apex"), Agdirected, nullptr), agclose);
  set(g.get(), "rankdir", "LR");
  set(g.get(), "nodesep", std::to_string(gap / kPointsPerInch));
  set(g.get(), "ranksep", std::to_string(gap / kPointsPerInch));
  std::map<std::string, Agnode_t*> nodes;
  for (const auto& [name, box] : boxes) {
    Agnode_t* n = agnode(g.get(), const_cast<char*>(name.c_str()), 1);
    set(n, "shape", "box");
    set(n, "fixedsize", "true");
    set(n, "width", std::to_string(box.width / kPointsPerInch));
    set(n, "height", std::to_string(box.height / kPointsPerInch));
    set(n, "label", "");
    nodes[name] = n;
  }
  for (const auto& [from, to] : edges) {
    auto a = nodes.find(from), b = nodes.find(to);
    if (a != nodes.end() && b != nodes.end() && a != b) agedge(g.get(), a->second, b->second, nullptr, 1);
  }
  if (gvLayout(gvc.get(), g.get(), "dot") != 0) {  // no layout: one column, in name order
    double y = 0;
    for (const auto& [name, box] : boxes) out[name] = {0, y}, y += box.height + gap;
    return out;
  }
  double left = std::numeric_limits<double>::max(), top = left;
  for (const auto& [name, n] : nodes) {  // centres, y up: to top-left corners, y down
    const Box& b = boxes.at(name);
    out[name] = {ND_coord(n).x - b.width / 2, -ND_coord(n).y - b.height / 2};
    left = std::min(left, out[name].first), top = std::min(top, out[name].second);
  }
  gvFreeLayout(gvc.get(), g.get());
  for (auto& [name, at] : out) at.first -= left, at.second -= top;
  return out;
}

Box freePlace(Box wanted, const std::vector<Box>& taken, double gap) {
  const double start_y = wanted.y;
  for (int column = 0;; ++column) {
    wanted.y = start_y;
    for (int tries = 0; tries < 50; ++tries) {
      auto hit = std::find_if(taken.begin(), taken.end(), [&](const Box& t) { return wanted.overlaps(t, gap); });
      if (hit == taken.end()) return wanted;
      wanted.y = hit->y + hit->height + gap;  // below what it hit
    }
    wanted.x += wanted.width + gap;  // a column full: the next one
  }
}

std::map<std::string, std::pair<double, double>> pushDown(const std::map<std::string, Box>& boxes, double gap) {
  std::vector<std::pair<std::string, Box>> order(boxes.begin(), boxes.end());
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.second.y < b.second.y; });
  std::vector<Box> done;
  std::map<std::string, std::pair<double, double>> moved;
  for (auto& [name, box] : order) {
    for (bool hit = true; hit;) {
      hit = false;
      for (const Box& d : done)
        if (box.overlaps(d)) box.y = d.y + d.height + gap, hit = true;
    }
    if (box.y != boxes.at(name).y) moved[name] = {box.x, box.y};
    done.push_back(box);
  }
  return moved;
}

}  // namespace apex_rviz_plugin
