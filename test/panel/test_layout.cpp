// Where the panel puts node boxes: layers from sources to sinks, never on top of
// each other (graphviz lays them out), and a free place for a new box.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "apex_rviz_plugin/layout.hpp"

using namespace apex_rviz_plugin;

namespace {

using Edges = std::vector<std::pair<std::string, std::string>>;

/** Each box placed where the layout says; the pairs that overlap, as text. */
std::string overlaps(std::map<std::string, Box> boxes, const std::map<std::string, std::pair<double, double>>& at) {
  for (auto& [name, b] : boxes) b.x = at.at(name).first, b.y = at.at(name).second;
  std::string out;
  for (auto a = boxes.begin(); a != boxes.end(); ++a)
    for (auto b = std::next(a); b != boxes.end(); ++b)
      if (a->second.overlaps(b->second)) out += a->first + " on " + b->first + "; ";
  return out;
}

TEST(Layout, TheDemoGraphInLayersLeftToRightWithNoBoxOnAnother) {
  // graphs/paper_pipeline.yaml's shape, with box heights as the panel draws them
  std::map<std::string, Box> boxes;
  const std::vector<std::pair<std::string, double>> sizes = {
      {"bag", 260},  {"gray", 120},        {"blur", 150},  {"threshold", 150},   {"morphology", 150}, {"blobs", 180},
      {"draw", 120}, {"overlay_out", 100}, {"voxel", 120}, {"passthrough", 150}, {"cloud_out", 100}};
  for (const auto& [name, h] : sizes) boxes[name] = Box{0, 0, 230, h};
  const Edges edges = {{"bag", "gray"},
                       {"gray", "blur"},
                       {"blur", "threshold"},
                       {"threshold", "morphology"},
                       {"morphology", "blobs"},
                       {"blobs", "draw"},
                       {"bag", "draw"},
                       {"draw", "overlay_out"},
                       {"bag", "voxel"},
                       {"voxel", "passthrough"},
                       {"passthrough", "cloud_out"}};
  const auto at = layeredLayout(boxes, edges);
  ASSERT_EQ(at.size(), boxes.size());
  EXPECT_EQ(overlaps(boxes, at), "");
  for (const auto& [from, to] : edges) EXPECT_LT(at.at(from).first, at.at(to).first) << from << " -> " << to;
  EXPECT_EQ(at.at("bag").first, 0);  // the top-left corner at (0, 0)
}

TEST(Layout, TwoHundredNodesWithCyclesAndNoBoxOnAnother) {
  std::mt19937 rng(7);
  std::map<std::string, Box> boxes;
  Edges edges;
  for (int i = 0; i < 200; ++i) {
    const std::string name = "n" + std::to_string(i);
    boxes[name] = Box{0, 0, 230, 60.0 + rng() % 240};
    if (i > 0) edges.emplace_back("n" + std::to_string(rng() % i), name);  // a tree growing...
    if (i % 17 == 0 && i > 0) edges.emplace_back(name, "n" + std::to_string(rng() % i));  // ...with cycles
  }
  const auto at = layeredLayout(boxes, edges);
  ASSERT_EQ(at.size(), 200u);
  EXPECT_EQ(overlaps(boxes, at), "");
  std::set<double> layers;
  for (const auto& [name, p] : at) layers.insert(p.first);
  EXPECT_GT(layers.size(), 5u);  // in layers, not one column
  int forward = 0;
  for (const auto& [from, to] : edges) forward += at.at(from).first < at.at(to).first;
  EXPECT_GT(forward, static_cast<int>(edges.size()) * 9 / 10);  // all but the cycles' back edges
}

TEST(Layout, AFreePlaceIsBelowWhatItWouldCoverOrInTheNextColumn) {
  const std::vector<Box> taken = {{0, 0, 100, 100}, {0, 120, 100, 100}};
  const Box below = freePlace({10, 10, 100, 50}, taken, 20);
  EXPECT_EQ(below.x, 10);
  EXPECT_EQ(below.y, 240);  // under both, 20 apart
  const Box free = freePlace({500, 0, 100, 50}, taken, 20);
  EXPECT_EQ(free.x, 500);
  EXPECT_EQ(free.y, 0);  // nothing there: where it was wanted
}

TEST(Layout, BoxesThatGrewPushThoseBelowDownAndKeepTheirColumn) {
  std::map<std::string, Box> boxes = {{"a", {0, 0, 100, 300}},  // grew from 100 to 300
                                      {"b", {0, 120, 100, 100}},
                                      {"c", {0, 240, 100, 100}},
                                      {"d", {300, 0, 100, 100}}};
  const auto moved = pushDown(boxes, 20);
  ASSERT_EQ(moved.size(), 2u);  // d, beside, stays
  EXPECT_EQ(moved.at("b"), std::make_pair(0.0, 320.0));
  EXPECT_EQ(moved.at("c"), std::make_pair(0.0, 440.0));
}

}  // namespace
