// The tuning demo's driver (scripts/demo --tune, launch/tune.launch): runs the Optimizer of
// graphs/tune_paper_pipeline.yaml on a training bag through the runtime's services, as a user
// would with rosservice, shows its progress, applies and saves the best values, and compares the
// shipped and the tuned parameters on a held-out bag.
//   apex_tune_report TRAIN.bag TRAIN_TRUTH.yaml TEST.bag TEST_TRUTH.yaml TUNED_GRAPH.yaml
#include <apex/SaveGraph.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Int32.h>
#include <yaml-cpp/yaml.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <map>
#include <mutex>
#include <stdexcept>

#include "runtime_client.hpp"

namespace {

using Clock = std::chrono::steady_clock;

using apex_tools::call;
using apex_tools::fire;
using apex_tools::graph;
using apex_tools::nodeIn;
using apex_tools::set;
using apex_tools::valueOf;

/** What the optimiser tunes: its output (dimension) → "node/parameter". */
std::map<std::string, std::string> targets(const apex::GraphState& g) {
  std::map<std::string, std::string> out;
  for (const auto& c : g.connections)
    if (c.from_node == "optimizer" && c.kind == "parameter") out[c.from_port] = c.to_node + "/" + c.to_port;
  return out;
}

/** The latest messages of the inspected ports, and a condition to wait on them. */
class Watch {
 public:
  explicit Watch(ros::NodeHandle& nh) {
    subs_.push_back(subscribe<std_msgs::Float64>(nh, "mean", "mean", [this](const auto& m) { ++means_, mean_ = m.data; }));
    subs_.push_back(subscribe<std_msgs::Int32>(nh, "optimizer", "evaluations", [this](const auto& m) { evaluations_ = m.data; }));
    subs_.push_back(subscribe<std_msgs::Float64>(nh, "optimizer", "best_fitness", [this](const auto& m) { best_ = m.data; }));
    for (auto& s : subs_)
      while (s.getNumPublishers() == 0 && ros::ok()) ros::WallDuration(0.01).sleep();
  }
  /** The mean of the next pass to end after now. */
  /** How many means have come so far: take it before the edit that starts a pass. */
  int means() {
    std::lock_guard<std::mutex> l(m_);
    return means_;
  }
  /** The first mean after the `seen`th (the pass's, however soon it ended). */
  double meanAfter(int seen, double timeout_s) {
    std::unique_lock<std::mutex> l(m_);
    if (!cv_.wait_for(l, std::chrono::duration<double>(timeout_s), [&] { return means_ > seen || !ros::ok(); }) || !ros::ok())
      throw std::runtime_error("no pass ended within " + std::to_string(static_cast<int>(timeout_s)) + " s");
    return mean_;
  }
  /** Waits up to `s` for the count of evaluations to pass `after`; the count now. */
  int evaluationsAfter(int after, double s) {
    std::unique_lock<std::mutex> l(m_);
    cv_.wait_for(l, std::chrono::duration<double>(s), [&] { return evaluations_ > after || !ros::ok(); });
    return evaluations_;
  }
  double best() {
    std::lock_guard<std::mutex> l(m_);
    return best_;
  }

 private:
  template <class Msg, class F>
  ros::Subscriber subscribe(ros::NodeHandle& nh, const std::string& node, const std::string& port, F on) {
    return nh.subscribe<Msg>(apex_tools::inspect(node, port), 100, [this, on](const typename Msg::ConstPtr& m) {
      std::lock_guard<std::mutex> l(m_);
      on(*m);
      cv_.notify_all();
    });
  }
  std::mutex m_;
  std::condition_variable cv_;
  std::vector<ros::Subscriber> subs_;
  int means_ = 0, evaluations_ = 0;
  double mean_ = 0, best_ = 0;
};

std::string bar(int done, int total) {
  const int width = 30, filled = total > 0 ? done * width / total : width;
  return "[" + std::string(filled, '#') + std::string(width - filled, '.') + "]";
}

double seconds(Clock::time_point since) { return std::chrono::duration<double>(Clock::now() - since).count(); }

/** Runs the optimiser to its end, printing progress at every tenth of the budget. */
void runOptimizer(Watch& watch, int budget, Clock::time_point t0) {
  fire("optimizer", "start");
  int done = 0, shown = 0;
  while (done < budget && ros::ok()) {
    const int now = watch.evaluationsAfter(done, 2.0);
    const auto& opt = nodeIn(graph(), "optimizer");
    if (opt.state == "error") throw std::runtime_error("the optimiser stopped: " + opt.error);
    if (now == done) continue;
    done = now;
    if (done * 10 / budget > shown || done == budget) {
      shown = done * 10 / budget;
      std::printf("%s %3d/%d evaluations  best F1 %.3f  (%.0f s)\n", bar(done, budget).c_str(), done, budget, watch.best(),
                  seconds(t0));
      std::fflush(stdout);
    }
  }
}

/** The run's best fitness and values, from the graph once the optimiser says it finished (the
 *  inspected outputs come on separate topics: the last may not be in yet). */
std::pair<double, std::string> finalBest() {
  const auto until = Clock::now() + std::chrono::seconds(30);
  for (;;) {
    const auto g = graph();
    const std::string state = YAML::Load(valueOf(g, "optimizer", "state")).as<std::string>();
    if (state.rfind("finished", 0) == 0) {
      const auto at = state.find("; best "), in = state.find(" at {");
      const double fitness =
          at != std::string::npos && in != std::string::npos ? std::stod(state.substr(at + 7, in - at - 7)) : 0;
      std::printf("optimiser: %s\n", state.c_str());
      for (const auto& p : YAML::Load(YAML::Load(valueOf(g, "optimizer", "front")).as<std::string>()))  // two objectives
        std::printf("  front: F1 %.3f at %.3f ms per frame, evaluation %d: %s\n", p["fitness"].as<double>(),
                    p["ms_per_frame"].as<double>(), p["evaluation"].as<int>(), YAML::Dump(p["values"]).c_str());
      return {fitness, YAML::Load(valueOf(g, "optimizer", "best_values")).as<std::string>()};
    }
    if (Clock::now() > until) throw std::runtime_error("the optimiser did not finish: " + state);
    ros::WallDuration(0.05).sleep();
  }
}

/** Whether two values are the same: numbers as numbers (30 is 30.0), words as words, an
 *  interval's ends one by one. */
bool sameValue(const YAML::Node& a, const YAML::Node& b) {
  if (a.IsSequence() && b.IsSequence()) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!sameValue(a[i], b[i])) return false;
    return true;
  }
  if (!a.IsScalar() || !b.IsScalar()) return false;
  try {
    return a.as<double>() == b.as<double>();
  } catch (const YAML::Exception&) {
    return a.Scalar() == b.Scalar();
  }
}

/** Waits until every tuned parameter holds the best value (apply_best works through the graph).
 *  An error of the optimiser's (a value it could not send) fails at once; the deadline only
 *  bounds a hang, on a loaded machine too. */
void waitApplied(const std::map<std::string, std::string>& tuned, const std::string& best_yaml) {
  const YAML::Node best = YAML::Load(best_yaml);
  const auto until = Clock::now() + std::chrono::seconds(60);
  for (;;) {
    const auto g = graph();
    bool all = true;
    for (const auto& [dim, target] : tuned) {
      const auto slash = target.find('/');
      all = all && sameValue(YAML::Load(valueOf(g, target.substr(0, slash), target.substr(slash + 1))), best[dim]);
    }
    if (all) return;
    for (const auto& n : g.nodes)
      if (n.name == "optimizer" && !n.error.empty()) throw std::runtime_error("apply_best: " + n.error);
    if (Clock::now() > until) throw std::runtime_error("apply_best did not reach the tuned parameters within 60 s");
    ros::WallDuration(0.05).sleep();
  }
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "apex_tune_report");
  if (argc < 6) {
    std::fprintf(stderr, "usage: apex_tune_report TRAIN.bag TRAIN_TRUTH.yaml TEST.bag TEST_TRUTH.yaml TUNED_GRAPH.yaml\n");
    return 2;
  }
  const std::string train_bag = argv[1], train_truth = argv[2], test_bag = argv[3], test_truth = argv[4], out = argv[5];
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const auto t0 = Clock::now();
  try {
    Watch watch(nh);
    const auto g0 = graph();
    const auto tuned = targets(g0);
    std::map<std::string, std::string> shipped;  // "node/parameter" → the graph's value
    for (const auto& [dim, target] : tuned)
      shipped[target] = valueOf(g0, target.substr(0, target.find('/')), target.substr(target.find('/') + 1));
    const int budget = std::stoi(valueOf(g0, "optimizer", "budget"));
    std::printf("\n=== APEX tune: %s over %zu parameters of the detector, budget %d evaluations\n",
                valueOf(g0, "optimizer", "algorithm").c_str(), tuned.size(), budget);

    // A pass with the shipped parameters first: the player plays once its bag is set.
    set("score", "truth", train_truth);
    int seen = watch.means();
    set("bag", "file", train_bag);
    const double train_shipped = watch.meanAfter(seen, 120);
    std::printf("training bag, shipped parameters: F1 %.3f\n", train_shipped);
    std::fflush(stdout);

    const auto run_start = Clock::now();
    runOptimizer(watch, budget, t0);
    const auto [best_fitness, best] = finalBest();
    std::printf("best on the training bag: F1 %.3f at %s\n", best_fitness, best.c_str());
    const std::string remote = valueOf(g0, "optimizer", "remote_workers");
    std::printf("the run took %.1f s with %s worker(s)%s\n", seconds(run_start), valueOf(g0, "optimizer", "workers").c_str(),
                remote == "[]" ? "" : (" here and those of " + remote).c_str());
    fire("optimizer", "apply_best");
    waitApplied(tuned, best);
    apex::SaveGraph::Request save;
    save.path = out;
    call<apex::SaveGraph>("save_graph", save);

    // Held out: the tuned values (applied), then the shipped ones, on a bag the search never saw.
    set("score", "truth", test_truth);
    seen = watch.means();
    set("bag", "file", test_bag);
    const double test_tuned = watch.meanAfter(seen, 120);
    for (const auto& [target, value] : shipped)
      set(target.substr(0, target.find('/')), target.substr(target.find('/') + 1), value);
    fire("mean", "reset");
    seen = watch.means();
    fire("bag", "restart");
    const double test_shipped = watch.meanAfter(seen, 120);

    std::printf("held-out bag:  shipped parameters F1 %.3f  ->  tuned F1 %.3f\n", test_shipped, test_tuned);
    std::printf("tuned graph:   %s\n", out.c_str());
    const bool ok = test_tuned > test_shipped;
    std::printf("tune: %s (%.0f s)\n", ok ? "OK" : "FAILED: the tuned parameters are not better on the held-out bag",
                seconds(t0));
    std::fflush(stdout);
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::printf("tune: FAILED: %s\n", e.what());
    std::fflush(stdout);
    return 1;
  }
}
