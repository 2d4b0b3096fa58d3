// The tuning loop's nodes: Optimizer, SequenceMean, RegionScore, on the loop of tuning_loop.hpp
// (workers and racing: test_tuning_workers).
#include <gmock/gmock.h>

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <thread>

#include "apex_nodes/types.hpp"
#include "apex_test/node_harness.hpp"
#include "tuning_loop.hpp"

using namespace apex_test;
using namespace apex_test::tuning;
using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace {

TEST(Optimizer, EachCandidateIsInEffectForEveryFrameOfItsEvaluationAndNoneOfThePrevious) {
  Loop loop(20);
  Graph& g = loop.g;
  ASSERT_TRUE(g.setParameter("opt", "algorithm", "random"));
  ASSERT_TRUE(g.setParameter("opt", "budget", "15"));
  g.start();
  ASSERT_TRUE(g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(g, "finished")) << paramText(g, "opt", "state");
  ASSERT_TRUE(g.waitIdle(kWait));

  const auto candidates = doubles(loop.candidates());
  ASSERT_EQ(candidates.size(), 16u) << "15 candidates, then the value from before the run";
  EXPECT_EQ(candidates.back(), 5.0);
  EXPECT_EQ(paramText(g, "probe", "gain"), "5.0") << "the run gives the tuned parameter its value back";
  const auto seen = doubles(loop.seen());
  ASSERT_EQ(seen.size(), 15u * 20u);
  for (std::size_t k = 0; k < 15; ++k)
    for (std::size_t f = 0; f < 20; ++f) ASSERT_EQ(seen[k * 20 + f], candidates[k]) << "evaluation " << k << ", frame " << f;
  const double best = *std::max_element(candidates.begin(), candidates.end() - 1);
  EXPECT_THAT(paramText(g, "opt", "state"), HasSubstr("finished after 15 evaluations; best "));
  EXPECT_THAT(paramText(g, "opt", "state"), HasSubstr("at {gain: " + toText(best) + "}"));
  EXPECT_EQ(g.nodeStats()[4].error, "");
}

TEST(Optimizer, TheSameSeedGivesTheSameCandidatesAndApplyBestSetsTheBest) {
  Loop loop(3);
  Graph& g = loop.g;
  ASSERT_TRUE(g.setParameter("opt", "budget", "12"));
  ASSERT_TRUE(g.setParameter("opt", "population", "5"));
  g.start();
  ASSERT_TRUE(g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(g, "finished"));
  ASSERT_TRUE(g.waitIdle(kWait));  // the tuned parameter's value from before the run has arrived
  ASSERT_TRUE(g.fireSlot("opt", "start"));
  // the second run may be over before a poll sees it running: wait for its candidates
  ASSERT_TRUE(waitUntil([&] { return loop.candidates()->size() >= 26u; }));
  ASSERT_TRUE(waitState(g, "finished"));
  ASSERT_TRUE(g.waitIdle(kWait));
  const auto c = doubles(loop.candidates());
  ASSERT_EQ(c.size(), 26u);
  EXPECT_EQ(std::vector<double>(c.begin(), c.begin() + 13), std::vector<double>(c.begin() + 13, c.end()));
  const double best = *std::max_element(c.begin(), c.begin() + 12);

  ASSERT_TRUE(g.fireSlot("opt", "apply_best"));
  ASSERT_TRUE(waitState(g, "applied"));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(paramText(g, "probe", "gain"), toText(best));
  EXPECT_THAT(paramText(g, "opt", "state"), HasSubstr("{gain: " + toText(best) + "}"));
}

TEST(Optimizer, RangesAndStepsComeFromTheTunedParameter) {
  Loop loop(2, "[gain, size int]");
  Graph& g = loop.g;
  link(g, "opt", "size", "probe", "size");
  add(g, "test/Collector", "sizes");
  link(g, "probe", "size_out", "sizes", "in");
  ASSERT_TRUE(g.setParameter("opt", "budget", "30"));
  g.start();
  ASSERT_TRUE(g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(g, "finished"));
  ASSERT_TRUE(g.waitIdle(kWait));
  for (double v : doubles(loop.seen())) EXPECT_TRUE(v >= 0 && v <= 100) << v;
  for (int v : object<Collector>(g, "sizes")->ints())
    if (v != -999) EXPECT_TRUE(v >= 3 && v <= 101 && v % 2 == 1) << v;
}

/** sequence → shape probe → mean → optimiser, which tunes the probe's window, mode and on. */
struct ShapeLoop {
  Graph g{registry()};
  explicit ShapeLoop(const std::string& dims) {
    add(g, "test/Sequence", "seq", "player");
    add(g, "test/ShapeProbe", "shape", "one");
    add(g, "apex_nodes/SequenceMean", "mean");
    add(g, "apex_nodes/Optimizer", "opt");
    add(g, "test/Collector", "windows");
    EXPECT_TRUE(g.setParameter("seq", "frames", "2"));
    EXPECT_TRUE(g.setParameter("opt", "dimensions", dims));
    link(g, "seq", "out", "shape", "in");
    link(g, "shape", "out", "mean", "value");
    link(g, "mean", "mean", "opt", "fitness");
    for (const char* p : {"window", "mode", "on"}) link(g, "opt", p, "shape", p);
    link(g, "opt", "window", "windows", "in");
    link(g, "opt", "evaluate", "seq", "restart");
    link(g, "opt", "evaluate", "mean", "reset");
  }
};

TEST(Optimizer, TunesBothEndsOfAnIntervalAChoiceAndAFlag) {
  ShapeLoop loop("[window interval 10 90, mode choice, on bool]");
  Graph& g = loop.g;
  ASSERT_TRUE(g.setParameter("opt", "budget", "400"));
  ASSERT_TRUE(g.setParameter("opt", "population", "20"));
  g.start();
  ASSERT_TRUE(g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(g, "finished", 120)) << paramText(g, "opt", "state");
  ASSERT_TRUE(g.waitIdle(kWait));
  std::vector<Interval> windows;
  for (const auto& m : object<Collector>(g, "windows")->messages())
    if (auto w = m.as<Interval>()) windows.push_back(*w);
  ASSERT_EQ(windows.size(), 401u) << "400 candidates, then the value from before the run";
  for (std::size_t i = 0; i + 1 < windows.size(); ++i) {
    const Interval& w = windows[i];
    ASSERT_TRUE(w.low >= 10 && w.low <= w.high && w.high <= 90 && w.low == std::round(w.low)) << w.low << " " << w.high;
  }
  EXPECT_EQ(paramText(g, "shape", "window"), "[0.0, 100.0]") << "the run gives the parameters their values back";
  EXPECT_EQ(paramText(g, "shape", "mode"), "a");

  const YAML::Node best = YAML::Load(paramText(g, "opt", "best_values"));
  EXPECT_EQ(best["mode"].as<std::string>(), "b");
  EXPECT_TRUE(best["on"].as<bool>());
  EXPECT_NEAR(best["window"][0].as<double>(), 20, 5);
  EXPECT_NEAR(best["window"][1].as<double>(), 60, 5);
  ASSERT_TRUE(g.fireSlot("opt", "apply_best"));
  ASSERT_TRUE(waitState(g, "applied"));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(paramText(g, "shape", "mode"), "b");
  EXPECT_EQ(paramText(g, "shape", "on"), "true");
  EXPECT_EQ(YAML::Load(paramText(g, "shape", "window")).as<std::vector<double>>(), best["window"].as<std::vector<double>>());
}

TEST(Optimizer, AChoiceOfAnOptionTheParameterLacksIsRefusedAtStart) {
  ShapeLoop loop("[window interval, mode choice a x, on bool]");
  Graph& g = loop.g;
  g.start();
  ASSERT_TRUE(g.fireSlot("opt", "start"));
  ASSERT_TRUE(g.waitIdle(kWait));
  std::string error;
  for (const auto& s : g.nodeStats())
    if (s.name == "opt") error = s.error;
  EXPECT_THAT(error, HasSubstr("dimension 'mode choice a x': 'x' is not an option of shape/mode"));
  EXPECT_THAT(g.setParameter("opt", "dimensions", "[on bool 0 1]").message(), HasSubstr("cannot read '0'"));
}

/** What describe_space says of the Optimizer's dimensions (python/apex/tuning.py samples it). */
YAML::Node describedSpace(Graph& g) {
  g.start();
  EXPECT_TRUE(g.fireSlot("opt", "describe_space"));
  EXPECT_TRUE(g.waitIdle(kWait));
  return YAML::Load(paramText(g, "opt", "space"));
}

TEST(Optimizer, DescribeSpaceGivesEachDimensionOnItsParametersGrid) {
  Loop loop(2, "[gain 10.5 20, size 4 50 int]");
  link(loop.g, "opt", "size", "probe", "size");
  const YAML::Node numbers = describedSpace(loop.g);
  ASSERT_EQ(numbers.size(), 2u) << numbers;
  EXPECT_EQ(numbers[0]["name"].as<std::string>(), "gain");
  EXPECT_EQ(numbers[0]["kind"].as<std::string>(), "number");
  EXPECT_EQ(numbers[0]["low"].as<double>(), 10.5);
  EXPECT_EQ(numbers[0]["high"].as<double>(), 20);
  EXPECT_FALSE(numbers[0]["step"]) << "a number is continuous";
  // size is 3, 5, ... 101: within 4 and 50, the first and last of them
  EXPECT_EQ(numbers[1]["kind"].as<std::string>(), "integer");
  EXPECT_EQ(numbers[1]["low"].as<int>(), 5);
  EXPECT_EQ(numbers[1]["high"].as<int>(), 49);
  EXPECT_EQ(numbers[1]["step"].as<int>(), 2);

  ShapeLoop shapes("[window interval 10.5 90.5, mode choice b c, on bool]");
  const YAML::Node others = describedSpace(shapes.g);
  ASSERT_EQ(others.size(), 3u) << others;
  EXPECT_EQ(others[0]["kind"].as<std::string>(), "interval");
  EXPECT_EQ(others[0]["low"].as<double>(), 11);
  EXPECT_EQ(others[0]["high"].as<double>(), 90);
  EXPECT_EQ(others[0]["step"].as<double>(), 1);
  EXPECT_EQ(others[1]["kind"].as<std::string>(), "choice");
  EXPECT_EQ(others[1]["options"].as<std::vector<std::string>>(), (std::vector<std::string>{"b", "c"}));
  EXPECT_EQ(others[2]["kind"].as<std::string>(), "flag");

  ASSERT_TRUE(shapes.g.setParameter("opt", "dimensions", "[window interval, mode choice, on bool, size 3 9 int]"));
  EXPECT_TRUE(shapes.g.fireSlot("opt", "describe_space"));
  ASSERT_TRUE(shapes.g.waitIdle(kWait));
  std::string error;
  for (const auto& s : shapes.g.nodeStats())
    if (s.name == "opt") error = s.error;
  EXPECT_THAT(error, HasSubstr("dimension 'size': its output feeds no parameter"));

  // a range with no value of the parameter in it: refused, as the start of a run refuses it
  ASSERT_TRUE(loop.g.setParameter("opt", "dimensions", "[gain, size 16 16 int]"));  // its links stay
  EXPECT_TRUE(loop.g.fireSlot("opt", "describe_space"));
  ASSERT_TRUE(loop.g.waitIdle(kWait));
  for (const auto& s : loop.g.nodeStats())
    if (s.name == "opt") error = s.error;
  EXPECT_THAT(error, HasSubstr("dimension 'size 16 16 int': no value of the parameter lies between 16 and 16 (it goes in "
                               "steps of 2 from 3)"));
}

TEST(Optimizer, ARunKilledHalfWayContinuesFromItsStudyToTheSameEnd) {
  const std::string study = ::testing::TempDir() + "/apex_study_" + std::to_string(::getpid()) + ".csv";
  std::remove(study.c_str());
  const auto settle = [](Loop& loop, const std::string& file) {
    EXPECT_TRUE(loop.g.setParameter("opt", "budget", "40"));
    EXPECT_TRUE(loop.g.setParameter("opt", "population", "8"));
    if (!file.empty()) EXPECT_TRUE(loop.g.setParameter("opt", "study", file));
  };
  std::vector<double> whole;  // an unbroken run's candidates, and the value from before it
  std::string best;
  {
    Loop loop(3);
    settle(loop, "");
    loop.g.start();
    ASSERT_TRUE(loop.g.fireSlot("opt", "start"));
    ASSERT_TRUE(waitState(loop.g, "finished"));
    ASSERT_TRUE(loop.g.waitIdle(kWait));
    whole = doubles(loop.candidates());
    best = paramText(loop.g, "opt", "best_values");
  }
  ASSERT_EQ(whole.size(), 41u);
  {  // the same run, its graph gone half-way with no end (as a kill)
    Loop loop(3);
    settle(loop, study);
    loop.g.start();
    ASSERT_TRUE(loop.g.fireSlot("opt", "start"));
    ASSERT_TRUE(waitUntil([&] { return doubles(loop.candidates()).size() >= 15u; }));
  }
  const std::size_t done = lines(study).size() - 2;  // the header and the column names
  ASSERT_GE(done, 10u);
  ASSERT_LT(done, 40u);
  EXPECT_EQ(lines(study)[1], "evaluation,fitness,gain");
  Loop loop(3);
  settle(loop, study);
  loop.g.start();
  ASSERT_TRUE(loop.g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(loop.g, "finished"));
  ASSERT_TRUE(loop.g.waitIdle(kWait));
  EXPECT_EQ(doubles(loop.candidates()), std::vector<double>(whole.begin() + done, whole.end()))
      << "the evaluations of the study are not made again; the rest are the unbroken run's";
  EXPECT_EQ(loop.seen()->size(), (40 - done) * 3);
  EXPECT_EQ(paramText(loop.g, "opt", "best_values"), best);
  EXPECT_EQ(lines(study).size(), 42u);

  // Another seed is another run: its study is refused, naming both
  ASSERT_TRUE(loop.g.setParameter("opt", "seed", "2"));
  ASSERT_TRUE(loop.g.fireSlot("opt", "start"));
  ASSERT_TRUE(loop.g.waitIdle(kWait));
  std::string error;
  for (const auto& st : loop.g.nodeStats())
    if (st.name == "opt") error = st.error;
  EXPECT_THAT(
      error, HasSubstr("the study '" + study + "' was made by another run (algorithm differential_evolution, budget 40, seed 1"));
  EXPECT_THAT(error, HasSubstr("this run is algorithm differential_evolution, budget 40, seed 2"));
  std::remove(study.c_str());
}

TEST(Optimizer, ThreeHundredEvaluationsOfAOneFrameSequenceRunThrough) {
  // The loop's own cost per evaluation (values, rewind, reset, tell) is a figure of
  // bench/loop_bench.cpp (~0.1 ms); here, printed: a test asserts no time, only that the run ends.
  Loop loop(1);
  Graph& g = loop.g;
  ASSERT_TRUE(g.setParameter("opt", "algorithm", "random"));
  ASSERT_TRUE(g.setParameter("opt", "budget", "300"));
  g.start();
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(g, "finished", 120));
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%.3f ms per evaluation\n", ms / 300);
}

TEST(Optimizer, StartRefusesWhatCannotRunAndSaysWhy) {
  Graph g(registry());
  add(g, "apex_nodes/Optimizer", "opt");
  g.start();
  ASSERT_TRUE(g.fireSlot("opt", "start"));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_THAT(g.nodeStats()[0].error, HasSubstr("no dimensions"));
  ASSERT_TRUE(g.setParameter("opt", "dimensions", "[c 0 60]"));
  ASSERT_TRUE(g.fireSlot("opt", "start"));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_THAT(g.nodeStats()[0].error, HasSubstr("dimension 'c': its output feeds no parameter"));
  auto bad = g.setParameter("opt", "dimensions", "[c 60 0]");
  ASSERT_FALSE(bad);
  EXPECT_THAT(bad.message(), HasSubstr("min is above max"));
  EXPECT_THAT(g.setParameter("opt", "dimensions", "[c zero]").message(), HasSubstr("cannot read 'zero'"));
  ASSERT_TRUE(g.fireSlot("opt", "apply_best"));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_THAT(g.nodeStats()[0].error, HasSubstr("no best values yet"));
}

/** A run that loses a tuned parameter mid-run: removed or unlinked. */
void loseATargetMidRun(const std::function<void(Graph&)>& cut) {
  Loop loop(30, "[gain 0 100, other 0 100]");
  Graph& g = loop.g;
  add(g, "test/Probe", "probe2", "three");
  link(g, "opt", "other", "probe2", "gain");
  ASSERT_TRUE(g.setParameter("opt", "budget", "1000"));
  g.start();
  ASSERT_TRUE(g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(g, "running: evaluation 3"));
  cut(g);
  ASSERT_TRUE(waitState(g, "stopped")) << paramText(g, "opt", "state");
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_THAT(g.nodeStats()[4].error, HasSubstr("dimension 'other' lost its parameter"));
  EXPECT_EQ(paramText(g, "probe", "gain"), "5.0") << "the parameter still tuned gets its value back";
  // the graph still runs: the sequence plays when asked
  const auto before = loop.seen()->size();
  ASSERT_TRUE(g.fireSlot("seq", "restart"));
  ASSERT_TRUE(loop.seen()->waitFor(before + 30));
}

TEST(Optimizer, RemovingATunedNodeMidRunStopsTheRunWithAnError) {
  loseATargetMidRun([](Graph& g) { ASSERT_TRUE(g.removeNode("probe2")); });
}

TEST(Optimizer, DisconnectingAnOutputMidRunStopsTheRunWithAnError) {
  loseATargetMidRun([](Graph& g) { ASSERT_TRUE(g.disconnect("opt", "other", "probe2", "gain")); });
}

TEST(Optimizer, AGraphSavedMidRunLoadsWithAClearErrorAndTheRunGoesOn) {
  Loop loop(30);
  Graph& g = loop.g;
  ASSERT_TRUE(g.setParameter("opt", "budget", "40"));
  g.start();
  ASSERT_TRUE(g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(g, "running: evaluation 2"));
  const GraphDescription saved = g.describe();

  Graph copy(registry());
  ASSERT_TRUE(copy.load(saved));
  copy.start();
  ASSERT_TRUE(copy.waitIdle(kWait));
  std::string error;
  for (const auto& s : copy.nodeStats())
    if (s.name == "opt") error = s.error;
  EXPECT_THAT(error, HasSubstr("saved while a run was in progress (running: evaluation"));
  EXPECT_THAT(paramText(copy, "opt", "state"), StartsWith("interrupted (running: evaluation"));
  ASSERT_TRUE(copy.fireSlot("seq", "restart"));  // a score nobody asked for leaves the error as it is
  ASSERT_TRUE(object<Collector>(copy, "seen")->waitFor(30));
  ASSERT_TRUE(copy.waitIdle(kWait));
  for (const auto& s : copy.nodeStats())
    if (s.name == "opt") EXPECT_THAT(s.error, HasSubstr("saved while a run was in progress"));
  ASSERT_TRUE(waitState(g, "finished", 60)) << "the original run went on";
}

TEST(SequenceMean, SendsTheMeanAtTheEndOfEachSequenceAndOnFinish) {
  Graph g(registry());
  add(g, "test/Sequence", "seq");
  add(g, "test/Probe", "probe");
  add(g, "apex_nodes/SequenceMean", "mean");
  add(g, "test/Collector", "means");
  add(g, "test/Collector", "counts");
  link(g, "seq", "out", "probe", "in");
  link(g, "probe", "out", "mean", "value");
  link(g, "mean", "mean", "means", "in");
  link(g, "mean", "count", "counts", "in");
  ASSERT_TRUE(g.setParameter("seq", "frames", "4"));
  g.start();
  ASSERT_TRUE(g.fireSlot("seq", "restart"));
  ASSERT_TRUE(object<Collector>(g, "means")->waitFor(5));
  ASSERT_TRUE(g.setParameter("probe", "gain", "7"));
  ASSERT_TRUE(g.waitIdle(kWait));
  ASSERT_TRUE(g.fireSlot("seq", "restart"));
  ASSERT_TRUE(object<Collector>(g, "means")->waitFor(10));
  ASSERT_TRUE(g.waitIdle(kWait));
  ASSERT_TRUE(g.fireSlot("mean", "finish"));  // by hand, with nothing since: 0 of 0
  ASSERT_TRUE(object<Collector>(g, "means")->waitFor(11));
  ASSERT_TRUE(g.waitIdle(kWait));
  EXPECT_EQ(doubles(object<Collector>(g, "means")), (std::vector<double>{5, 7, 0}));
  std::vector<int> counts;
  for (int c : object<Collector>(g, "counts")->ints())
    if (c != -999) counts.push_back(c);
  EXPECT_EQ(counts, (std::vector<int>{4, 4, 0}));
}

// ---------------------------------------------------------------- RegionScore

apex_nodes::Regions regions(std::uint64_t stamp_ns, cv::Size size, std::vector<cv::Rect> boxes) {
  apex_nodes::Regions r;
  r.header.stamp.fromNSec(stamp_ns);
  r.image_size = size;
  for (const auto& b : boxes) r.regions.push_back({b, static_cast<double>(b.area()), {}});
  return r;
}

std::string writeTruth(const std::string& text) {
  static int files = 0;
  const std::string path =
      ::testing::TempDir() + "/apex_truth_" + std::to_string(::getpid()) + "_" + std::to_string(++files) + ".yaml";
  std::ofstream(path) << text;
  return path;
}

double scoreOf(NodeHarness& h, const apex_nodes::Regions& r) {
  const Message m = h.run({Message::make(r)});
  return m.isNothing() ? -1 : *m.as<double>();
}

TEST(RegionScore, MatchesBoxesByStampAndOverlapThroughTheCameraRotation) {
  const std::string truth = writeTruth(
      "scene_size: [640, 480]\ncamera_rotation: 90\nframes:\n"
      "  - {stamp: 1000000000, signs: 2, boxes: [[100, 50, 80, 60], [300, 200, 100, 100]]}\n"
      "  - {stamp: 1100000000, signs: 0, boxes: []}\n");
  NodeHarness h("apex_nodes/RegionScore", {"regions"}, "f1");
  h.set("truth", truth);
  const cv::Size upright(640, 480), turned(480, 640);
  // both found, upright
  EXPECT_DOUBLE_EQ(scoreOf(h, regions(1000000000, upright, {{102, 52, 80, 60}, {300, 200, 100, 100}})), 1.0);
  // one found, one false region: precision 1/2, recall 1/2
  EXPECT_DOUBLE_EQ(scoreOf(h, regions(1000000000, upright, {{100, 50, 80, 60}, {0, 0, 10, 10}})), 0.5);
  // the same two in the camera's turned image: x' = 480 - y - h, y' = x
  EXPECT_DOUBLE_EQ(scoreOf(h, regions(1000000000, turned, {{370, 100, 60, 80}, {180, 300, 100, 100}})), 1.0);
  // the stamp within a millisecond; an empty frame found empty scores 1
  EXPECT_DOUBLE_EQ(scoreOf(h, regions(1100000300, upright, {})), 1.0);
  // one region where there is nothing: precision 0, recall 1, F1 0
  EXPECT_DOUBLE_EQ(scoreOf(h, regions(1100000000, upright, {{1, 1, 5, 5}})), 0.0);
  // a stamp the truth does not have, an image of another size: errors naming them
  EXPECT_EQ(scoreOf(h, regions(5000000000, upright, {})), -1);
  EXPECT_THAT(h.error(), HasSubstr("has no frame at stamp 5"));
  EXPECT_EQ(scoreOf(h, regions(1000000000, cv::Size(100, 100), {})), -1);
  EXPECT_THAT(h.error(), HasSubstr("the regions come from a 100x100 image"));
  h.set("truth", writeTruth("frames: [oops"));
  EXPECT_EQ(scoreOf(h, regions(1000000000, upright, {})), -1);
  EXPECT_THAT(h.error(), HasSubstr("cannot read the ground truth"));
  // only_labelled: a frame the truth lacks (a bag labelled in part) gives Nothing and no error
  h.set("truth", truth);
  h.set("only_labelled", "true");
  EXPECT_EQ(scoreOf(h, regions(5000000000, upright, {})), -1);
  EXPECT_EQ(h.error(), "");
  EXPECT_DOUBLE_EQ(scoreOf(h, regions(1000000000, upright, {{100, 50, 80, 60}, {0, 0, 10, 10}})), 0.5);
}

}  // namespace
