// The tuning loop of test_tuning and test_tuning_workers, as in graphs/tune_paper_pipeline.yaml
// with a short sequence in place of the bag and a probe in place of the detector: each frame
// reports the probe's parameter, so the score of a candidate is its own value exactly when its
// values were in effect for every frame of its evaluation.
#pragma once

#include <gmock/gmock.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "apex_test/node_harness.hpp"

namespace apex_test {
namespace tuning {

/** Per frame, sends the value of its parameter `gain`; `size` steps by 2 (odd sizes). */
class Probe : public Node {
 public:
  static Manifest manifest() {
    return Manifest("reports its parameters per frame")
        .input<int>("in")
        .output<double>("out")
        .output<int>("size_out")
        .param(param::range("gain", 0.0, 100.0, 0.0, 5.0).makeInteractive())
        .param(param::range("size", 3, 101, 2, 3).makeInteractive());
  }
  void process() override {
    publish("out", param<double>("gain"));
    publish("size_out", param<int>("size"));
  }
};

/** Per frame, scores its interval, choice and flag: 2 at window [20, 60], mode b and on. */
class ShapeProbe : public Node {
 public:
  static Manifest manifest() {
    return Manifest("scores its interval, choice and flag per frame")
        .input<int>("in")
        .output<double>("out")
        .param(param::interval("window", 0.0, 100.0, 0.0, 100.0, 1.0).makeInteractive())
        .param(param::options("mode", {"a", "b", "c"}, "a").makeInteractive())
        .param(param::boolean("on", false).makeInteractive());
  }
  void process() override {
    const auto w = param<Interval>("window");
    publish("out", (param<std::string>("mode") == "b" ? 1.0 : 0.0) + (param<bool>("on") ? 1.0 : 0.0) -
                       (std::abs(w.low - 20) + std::abs(w.high - 60)) / 100.0);
  }
};

/** Per frame, works gain x 20 us (a cost that grows with gain) and scores -(gain - 50)^2: gains
 *  above 50 are beaten on both by one as far below 50 (as fit, and cheaper). */
class SlowProbe : public Node {
 public:
  static Manifest manifest() {
    return Manifest("works in proportion to its gain per frame, and scores how near 50 it is")
        .input<int>("in")
        .output<double>("out")
        .param(param::range("gain", 0.0, 100.0, 0.0, 5.0).makeInteractive());
  }
  void process() override {
    const double gain = param<double>("gain");
    const auto until = std::chrono::steady_clock::now() + std::chrono::nanoseconds(static_cast<long>(gain * 20'000));
    while (std::chrono::steady_clock::now() < until) {
    }
    publish("out", -(gain - 50) * (gain - 50));
  }
};

inline const NodeRegistry& registry() {
  static NodeRegistry* r = [] {
    auto* reg = new NodeRegistry(pluginRegistry());
    EXPECT_TRUE(reg->add<Probe>("test/Probe"));
    EXPECT_TRUE(reg->add<ShapeProbe>("test/ShapeProbe"));
    EXPECT_TRUE(reg->add<SlowProbe>("test/SlowProbe"));
    return reg;
  }();
  return *r;
}

/** A parameter's value as text; a string as it is. */
inline std::string paramText(Graph& g, const std::string& node, const std::string& name) {
  const ParamValue v = g.parameterValue(node, name).value();
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  return toText(v);
}

/** Waits until the optimiser's state starts with `prefix`. */
inline bool waitState(Graph& g, const std::string& prefix, double timeout = kWait) {
  return waitUntil([&] { return paramText(g, "opt", "state").rfind(prefix, 0) == 0; }, timeout);
}

inline std::vector<double> doubles(Collector* c) {
  std::vector<double> out;
  for (const auto& m : c->messages())
    if (auto v = m.as<double>()) out.push_back(*v);
  return out;
}

/** sequence → relay → probe → mean → optimiser, the optimiser's `gain` → the probe's gain;
 *  evaluate → restart and reset. Four thread groups. */
struct Loop {
  Graph g{registry()};
  explicit Loop(int frames = 20, const std::string& dims = "[gain 0 100]", const std::string& probe = "test/Probe") {
    add(g, "test/Sequence", "seq", "player");
    add(g, "test/Relay", "relay", "one");
    add(g, probe, "probe", "two");
    add(g, "apex_nodes/SequenceMean", "mean");
    add(g, "apex_nodes/Optimizer", "opt");
    add(g, "test/Collector", "seen");  // what the probe reports, per frame
    add(g, "test/Collector", "candidates");  // what the optimiser sends
    EXPECT_TRUE(g.setParameter("seq", "frames", std::to_string(frames)));
    EXPECT_TRUE(g.setParameter("opt", "dimensions", dims));
    link(g, "seq", "out", "relay", "in");
    link(g, "relay", "out", "probe", "in");
    link(g, "probe", "out", "mean", "value");
    link(g, "probe", "out", "seen", "in");
    link(g, "mean", "mean", "opt", "fitness");
    link(g, "opt", "gain", "probe", "gain");
    link(g, "opt", "gain", "candidates", "in");
    link(g, "opt", "evaluate", "seq", "restart");
    link(g, "opt", "evaluate", "mean", "reset");
  }
  Collector* seen() { return object<Collector>(g, "seen"); }
  Collector* candidates() { return object<Collector>(g, "candidates"); }
};

/** The lines of a file. */
inline std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

/** A run of `workers`  written to a study: its rows after the two header lines. */
inline std::vector<std::string> studyOfRun(const std::string& algorithm, int workers, Loop& loop) {
  const std::string study = ::testing::TempDir() + "/apex_workers_" + std::to_string(::getpid()) + ".csv";
  std::remove(study.c_str());
  EXPECT_TRUE(loop.g.setParameter("opt", "algorithm", algorithm));
  EXPECT_TRUE(loop.g.setParameter("opt", "budget", "40"));
  EXPECT_TRUE(loop.g.setParameter("opt", "population", "8"));
  EXPECT_TRUE(loop.g.setParameter("opt", "workers", std::to_string(workers)));
  EXPECT_TRUE(loop.g.setParameter("opt", "study", study));
  loop.g.start();
  EXPECT_TRUE(loop.g.fireSlot("opt", "start"));
  EXPECT_TRUE(waitState(loop.g, "finished")) << paramText(loop.g, "opt", "state");
  EXPECT_TRUE(loop.g.waitIdle(kWait));
  auto rows = lines(study);
  std::remove(study.c_str());
  return rows.size() < 2 ? rows : std::vector<std::string>(rows.begin() + 2, rows.end());
}

/** "k,fitness,gain": whether the fitness is the gain (the candidate was in effect for every frame). */
inline bool scoredItsOwnValue(const std::string& row) {
  const auto a = row.find(','), b = row.find(',', a + 1);
  const double fitness = std::stod(row.substr(a + 1, b - a - 1)), gain = std::stod(row.substr(b + 1));
  return std::abs(fitness - gain) <= 1e-12 * std::max(1.0, gain);  // the mean of 20 equal numbers, rounded
}
}  // namespace tuning
}  // namespace apex_test
