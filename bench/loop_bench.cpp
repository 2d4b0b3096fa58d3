// The tuning loop's own cost per evaluation: setting the candidate's values, rewinding the
// sequence, resetting the mean and telling the fitness, without the pipeline's processing.
// The loop of graphs/tune_paper_pipeline.yaml (Optimizer, SequenceMean, a player's restart,
// three thread groups) runs around a trivial pipeline whose sequences have 1 or 21 frames;
// interleaved and repeated. A frame's cost is (t21 - t1) / 20 in the same run; the loop's own
// cost is t1 minus one frame.
//   apex_bench_loop [--quick]   (with the devel space sourced: node types come from pluginlib)
#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>

#include "apex/core/graph.hpp"
#include "plugin_registry.hpp"
#include "spread.hpp"

using namespace apex;
using Clock = std::chrono::steady_clock;
using apex_bench::Spread;

namespace {

/** A driven source: on `restart`, frames 0..n-1, then the end of the sequence. */
class Sequence : public Node {
 public:
  static Manifest manifest() {
    return Manifest().output<int>("out").slot("restart", &Sequence::restart).param(param::integer("frames", 1)).driven();
  }
  void restart() {
    next_ = 0;
    notifyNewData();
  }
  void process() override {
    if (next_ < 0) return;
    if (next_ == frames_.get()) {
      next_ = -1;
      return endSequence();
    }
    out_.publish(next_++);
    notifyNewData();
  }

 private:
  Output<int> out_{this, "out"};
  Param<int> frames_{this, "frames"};
  int next_ = -1;
};

/** The pipeline: per frame, the value of its tuned parameter. */
class Probe : public Node {
 public:
  static Manifest manifest() {
    return Manifest().input<int>("in").output<double>("out").param(param::range("gain", 0.0, 100.0, 0.0, 1.0).makeInteractive());
  }
  void process() override { out_.publish(gain_.get()); }

 private:
  Output<double> out_{this, "out"};
  Param<double> gain_{this, "gain"};
};

NodeRegistry& registry() {
  return apex_bench::pluginRegistry([](NodeRegistry& r) {
    (void)r.add<Sequence>("bench/Sequence");
    (void)r.add<Probe>("bench/Probe");
  });
}

void must(const Status& st) {
  if (!st) {
    std::fprintf(stderr, "apex_bench_loop: %s\n", st.message().c_str());
    std::exit(1);
  }
}

/** Microseconds per evaluation of a run of `evaluations` on sequences of `frames`. */
double perEvaluation(int frames, int evaluations) {
  Graph g(registry());
  for (auto [type, name, group] : {std::tuple{"bench/Sequence", "seq", "player"},
                                   {"bench/Probe", "probe", "vision"},
                                   {"apex_nodes/SequenceMean", "mean", "tuning"},
                                   {"apex_nodes/Optimizer", "opt", "tuning"}})
    must(g.addNode(type, name, group).status());
  must(g.setParameter("seq", "frames", std::to_string(frames)).status());
  must(g.setParameter("opt", "dimensions", "[gain 0 100]").status());
  must(g.setParameter("opt", "algorithm", "random").status());
  must(g.setParameter("opt", "budget", std::to_string(evaluations)).status());
  must(g.connect("seq", "out", "probe", "in"));
  must(g.connect("probe", "out", "mean", "value"));
  must(g.connect("mean", "mean", "opt", "fitness"));
  must(g.connect("opt", "gain", "probe", "gain"));
  must(g.connect("opt", "evaluate", "seq", "restart"));
  must(g.connect("opt", "evaluate", "mean", "reset"));
  g.start();
  const auto t0 = Clock::now();
  must(g.fireSlot("opt", "start"));
  for (;;) {
    const auto state = std::get<std::string>(g.parameterValue("opt", "state").value());
    if (state.rfind("finished", 0) == 0) break;
    if (Clock::now() - t0 > std::chrono::seconds(120)) {
      std::fprintf(stderr, "apex_bench_loop: the run did not finish: %s\n", state.c_str());
      std::exit(1);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  const double us = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
  g.stop();
  return us / evaluations;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const int repeats = quick ? 3 : 9, evaluations = quick ? 300 : 1000;
  Spread one, many, frame, loop;
  for (int r = 0; r < repeats; ++r) {
    const double t1 = perEvaluation(1, evaluations), t21 = perEvaluation(21, evaluations);
    one.add(t1);
    many.add(t21);
    frame.add((t21 - t1) / 20);
    loop.add(t1 - (t21 - t1) / 20);
  }
  std::printf("## The tuning loop's own cost per evaluation\n\n");
  std::printf(
      "The loop of graphs/tune_paper_pipeline.yaml (Optimizer, SequenceMean, a player's restart; three thread\n"
      "groups) around a trivial pipeline, %d evaluations per run, runs of 1-frame and 21-frame sequences\n"
      "interleaved, %d each; median (min–max), microseconds.\n\n",
      evaluations, repeats);
  std::printf("| | per evaluation |\n|---|---|\n");
  std::printf("| sequence of 1 frame | %s µs |\n", one.text("%.1f").c_str());
  std::printf("| sequence of 21 frames | %s µs |\n", many.text("%.1f").c_str());
  std::printf("| one frame (baseline: (21 − 1) / 20) | %s µs |\n", frame.text("%.1f").c_str());
  std::printf("| **the loop's own cost** (1 frame − one frame) | **%s µs** = %.1f× a frame |\n", loop.text("%.1f").c_str(),
              loop.median() / frame.median());
  return 0;
}
