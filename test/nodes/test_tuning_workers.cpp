// The Optimizer's workers (copies of the evaluated part beside the graph) and racing (cutting a
// candidate's pass once it cannot count), on the loop of tuning_loop.hpp: each study row's fitness
// is its candidate's gain exactly when the candidate was in effect for every frame of its pass.
// Two objectives: fitness and the tuned nodes' ms per frame, and the Pareto front of the two.
#include <gmock/gmock.h>
#include <unistd.h>

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "apex_nodes/pareto.hpp"
#include "tuning_loop.hpp"

using namespace apex_test;
using namespace apex_test::tuning;
using ::testing::HasSubstr;

namespace {

TEST(Optimizer, WorkersEvaluateInCopiesBesideTheRestingGraphWithTheSameCandidatesAndResults) {
  Loop one(20), three(20);
  const auto serial = studyOfRun("random", 1, one);
  const auto parallel = studyOfRun("random", 3, three);
  ASSERT_EQ(serial.size(), 40u);
  EXPECT_EQ(parallel, serial) << "the same candidates, each scored as in the graph, in the order asked";
  for (const auto& row : parallel) EXPECT_TRUE(scoredItsOwnValue(row)) << row;
  EXPECT_EQ(paramText(three.g, "opt", "best_values"), paramText(one.g, "opt", "best_values"));
  EXPECT_TRUE(doubles(three.candidates()).empty()) << "the graph rests: no candidate, and nothing to give back";
  EXPECT_EQ(three.seen()->size(), 0u);
  EXPECT_EQ(paramText(three.g, "probe", "gain"), "5.0");
  EXPECT_EQ(three.g.size(), one.g.size()) << "the copies are not part of the graph";
}

TEST(Optimizer, DifferentialEvolutionWithWorkersScoresAGenerationAtOnceAndRepeatsItsRun) {
  Loop a(5), b(5);
  const auto first = studyOfRun("differential_evolution", 2, a);
  const auto second = studyOfRun("differential_evolution", 2, b);
  ASSERT_EQ(first.size(), 40u);
  EXPECT_EQ(first, second) << "the same seed gives the same run, whichever worker is faster";
  for (const auto& row : first) EXPECT_TRUE(scoredItsOwnValue(row)) << row;
}

/** The fitness column of a study row. */
double fitnessOf(const std::string& row) {
  const auto a = row.find(',');
  return std::stod(row.substr(a + 1, row.find(',', a + 1) - a - 1));
}

TEST(Optimizer, RacingCutsPoorCandidatesShortAndTakesTheSameCourse) {
  for (int workers : {1, 2}) {
    SCOPED_TRACE("workers " + std::to_string(workers));
    Loop whole(20), raced(20);
    for (Loop* l : {&whole, &raced}) ASSERT_TRUE(l->g.setParameter("opt", "frame_score_bound", "100"));
    link(raced.g, "mean", "running", "opt", "running");
    link(raced.g, "opt", "cut", "seq", "end_pass");
    ASSERT_TRUE(raced.g.setParameter("opt", "racing", "true"));
    ASSERT_TRUE(raced.g.setParameter("opt", "racing_rule", "bound"));
    const auto expected = studyOfRun("differential_evolution", workers, whole);
    const auto rows = studyOfRun("differential_evolution", workers, raced);
    ASSERT_EQ(rows.size(), 40u);
    EXPECT_EQ(paramText(raced.g, "opt", "best_values"), paramText(whole.g, "opt", "best_values"));
    int cut = 0;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      if (rows[k] == expected[k]) continue;  // scored on every frame: as without racing
      ++cut;
      EXPECT_GT(fitnessOf(rows[k]), fitnessOf(expected[k])) << "a cut candidate counts as the most it could have scored";
    }
    EXPECT_GT(cut, 5);
    EXPECT_THAT(paramText(raced.g, "opt", "state"), HasSubstr("(racing bound: " + std::to_string(cut) + " cut short, "));
    if (workers == 1) EXPECT_LT(raced.seen()->size(), whole.seen()->size() * 0.9) << "fewer frames scored";
  }
}

TEST(Optimizer, PairedRacingCutsEarlierThanTheBoundAndHereTakesTheSameCourse) {
  // Each frame scores the candidate's gain: the differences to its rival are the same on every
  // frame, so a candidate below its rival is clearly worse after 5 frames, and its estimate is exact.
  for (int workers : {1, 2}) {
    SCOPED_TRACE("workers " + std::to_string(workers));
    Loop whole(20), bound(20), paired(20);
    for (Loop* l : {&whole, &bound, &paired}) ASSERT_TRUE(l->g.setParameter("opt", "frame_score_bound", "100"));
    for (Loop* l : {&bound, &paired}) {
      link(l->g, "mean", "running", "opt", "running");
      link(l->g, "opt", "cut", "seq", "end_pass");
      ASSERT_TRUE(l->g.setParameter("opt", "racing", "true"));
    }
    ASSERT_TRUE(bound.g.setParameter("opt", "racing_rule", "bound"));
    const auto expected = studyOfRun("differential_evolution", workers, whole);
    (void)studyOfRun("differential_evolution", workers, bound);
    const auto rows = studyOfRun("differential_evolution", workers, paired);
    ASSERT_EQ(rows.size(), expected.size());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      EXPECT_EQ(rows[k].substr(rows[k].rfind(',')), expected[k].substr(expected[k].rfind(','))) << "the same candidates";
      // cut by the paired rule: its estimate, exact here; by the bound first: the bound, above
      EXPECT_GE(fitnessOf(rows[k]), fitnessOf(expected[k]) - 1e-9) << rows[k];
    }
    EXPECT_EQ(paramText(paired.g, "opt", "best_values"), paramText(whole.g, "opt", "best_values"));
    const auto share = [](Loop& l) {
      const std::string st = paramText(l.g, "opt", "state");
      const auto at = st.find(" cut short, ");
      return at == std::string::npos ? 100 : std::stoi(st.substr(at + 12));
    };
    EXPECT_LT(share(paired), share(bound)) << paramText(paired.g, "opt", "state") << " against "
                                           << paramText(bound.g, "opt", "state");
    if (workers == 1) EXPECT_LT(paired.seen()->size(), bound.seen()->size()) << "fewer frames through the graph";
  }
}

TEST(Optimizer, RacingWithABoundScoresBeatTurnsItselfOffAndTheRunIsTheSame) {
  Loop whole(20), raced(20);
  link(raced.g, "mean", "running", "opt", "running");
  link(raced.g, "opt", "cut", "seq", "end_pass");
  ASSERT_TRUE(raced.g.setParameter("opt", "racing", "true"));  // frame_score_bound 1: the gains reach 100
  const auto expected = studyOfRun("random", 1, whole);
  EXPECT_EQ(studyOfRun("random", 1, raced), expected);
  EXPECT_THAT(paramText(raced.g, "opt", "state"), HasSubstr("(racing paired: 0 cut short, "));
}

TEST(Optimizer, RemovingItMidRunWithWorkersLeavesTheGraphRunning) {
  for (int round = 0; round < 5; ++round) {
    Loop loop(20);
    link(loop.g, "mean", "running", "opt", "running");  // the copies' taps call in at every frame
    link(loop.g, "opt", "cut", "seq", "end_pass");
    ASSERT_TRUE(loop.g.setParameter("opt", "workers", "3"));
    ASSERT_TRUE(loop.g.setParameter("opt", "racing", "true"));
    ASSERT_TRUE(loop.g.setParameter("opt", "frame_score_bound", "100"));
    ASSERT_TRUE(loop.g.setParameter("opt", "budget", "100000"));
    loop.g.start();
    ASSERT_TRUE(loop.g.fireSlot("opt", "start"));
    ASSERT_TRUE(waitUntil([&] {
      const std::string st = paramText(loop.g, "opt", "state"), at = "running: evaluation ";
      return st.rfind(at, 0) == 0 && std::stoi(st.substr(at.size())) >= 5;
    }));
    ASSERT_TRUE(loop.g.removeNode("opt"));
    ASSERT_TRUE(loop.g.fireSlot("seq", "restart"));  // the graph still plays
    ASSERT_TRUE(loop.seen()->waitFor(20));
  }
}

TEST(Optimizer, WorkersNeedTheFitnessToComeFromTheEvaluatedPart) {
  Loop loop(3);
  ASSERT_TRUE(loop.g.disconnect("opt", "evaluate", "seq", "restart"));
  ASSERT_TRUE(loop.g.disconnect("opt", "evaluate", "mean", "reset"));
  ASSERT_TRUE(loop.g.setParameter("opt", "workers", "2"));
  loop.g.start();
  ASSERT_TRUE(loop.g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(loop.g, "stopped"));
  std::string error;
  ASSERT_TRUE(waitUntil([&] {
    for (const auto& st : loop.g.nodeStats())
      if (st.name == "opt") error = st.error;
    return !error.empty();
  }));
  EXPECT_THAT(error, HasSubstr("workers 2: its 'evaluate' reaches none of the nodes the fitness comes from"));
}
}  // namespace

// ---------------------------------------------------------------- two objectives

namespace {

using apex_nodes::tuning::Scored;

/** A study row of a two-objective run, "k,fitness,ms_per_frame,gain". */
Scored rowOf(const std::string& row) {
  std::vector<double> v;
  std::stringstream in(row);
  for (std::string f; std::getline(in, f, ',');) v.push_back(std::stod(f));
  return {static_cast<int>(v.at(0)), v.at(1), v.at(2), {v.at(3)}};
}

/** The evaluations no other row beats on both fitness (larger) and cost (smaller). */
std::set<int> nonDominated(const std::vector<Scored>& rows) {
  std::set<int> out;
  for (const auto& a : rows)
    if (std::none_of(rows.begin(), rows.end(), [&](const Scored& b) { return apex_nodes::tuning::dominates(b, a, false); }))
      out.insert(a.evaluation);
  return out;
}

/** The evaluations named by the optimiser's `front`, in its order. */
std::vector<int> frontOf(Graph& g) {
  std::vector<int> out;
  for (const auto& p : YAML::Load(paramText(g, "opt", "front"))) out.push_back(p["evaluation"].as<int>());
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

}  // namespace

TEST(Pareto, APointJoinsTheFrontUnlessBeatenOnBothAndDropsWhatItBeats) {
  std::vector<Scored> front;
  EXPECT_TRUE(apex_nodes::tuning::addToFront(front, {1, 0.5, 2.0, {}}, false));
  EXPECT_TRUE(apex_nodes::tuning::addToFront(front, {2, 0.9, 5.0, {}}, false));  // fitter, dearer: both stay
  EXPECT_FALSE(apex_nodes::tuning::addToFront(front, {3, 0.4, 3.0, {}}, false));  // beaten by 1 on both
  EXPECT_FALSE(apex_nodes::tuning::addToFront(front, {4, 0.5, 2.0, {}}, false));  // as good as 1, no better
  EXPECT_TRUE(apex_nodes::tuning::addToFront(front, {5, 0.6, 1.0, {}}, false));  // beats 1 on both
  ASSERT_EQ(front.size(), 2u);
  EXPECT_EQ(front[0].evaluation, 5);  // cheapest first
  EXPECT_EQ(front[1].evaluation, 2);
  std::vector<Scored> least;  // minimize: the smaller fitness is the better
  EXPECT_TRUE(apex_nodes::tuning::addToFront(least, {1, 0.5, 2.0, {}}, true));
  EXPECT_FALSE(apex_nodes::tuning::addToFront(least, {2, 0.9, 3.0, {}}, true));
}

TEST(Optimizer, TwoObjectivesKeepTheFrontOfFitnessAndTheTunedNodesMsPerFrame) {
  const std::string study = ::testing::TempDir() + "/apex_front_" + std::to_string(::getpid()) + ".csv";
  std::remove(study.c_str());
  Loop loop(8, "[gain 0 100]", "test/SlowProbe");
  ASSERT_TRUE(loop.g.setParameter("opt", "objectives", "fitness_and_cost"));
  ASSERT_TRUE(loop.g.setParameter("opt", "algorithm", "random"));
  ASSERT_TRUE(loop.g.setParameter("opt", "budget", "30"));
  ASSERT_TRUE(loop.g.setParameter("opt", "study", study));
  loop.g.start();
  ASSERT_TRUE(loop.g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(loop.g, "finished")) << paramText(loop.g, "opt", "state");
  ASSERT_TRUE(loop.g.waitIdle(kWait));

  const auto rows = lines(study);
  ASSERT_EQ(rows.size(), 32u);
  EXPECT_EQ(rows[1], "evaluation,fitness,ms_per_frame,gain");
  std::vector<Scored> scored;
  std::vector<double> cheap, dear;  // the cost of gains up to 30, and from 70
  for (std::size_t i = 2; i < rows.size(); ++i) {
    const Scored s = rowOf(rows[i]);
    EXPECT_NEAR(s.fitness, -(s.point[0] - 50) * (s.point[0] - 50), 1e-9) << rows[i];
    EXPECT_GE(s.cost_ms, s.point[0] * 0.02 * 0.99) << "at least the probe's busy time: " << rows[i];
    if (s.point[0] <= 30) cheap.push_back(s.cost_ms);
    if (s.point[0] >= 70) dear.push_back(s.cost_ms);
    scored.push_back(s);
  }
  ASSERT_FALSE(cheap.empty());
  ASSERT_FALSE(dear.empty());
  EXPECT_GT(median(dear), median(cheap) + 0.5) << "the cost grows with the work the gain asks for (20 us a unit)";

  const std::vector<int> front = frontOf(loop.g);
  EXPECT_EQ(std::set<int>(front.begin(), front.end()), nonDominated(scored)) << paramText(loop.g, "opt", "front");
  EXPECT_GE(front.size(), 2u) << "fitness near 50 costs more than a low gain: a trade-off";
  for (std::size_t i = 1; i < front.size(); ++i)
    EXPECT_LT(scored[front[i - 1] - 1].cost_ms, scored[front[i] - 1].cost_ms) << "cheapest first";
  EXPECT_THAT(paramText(loop.g, "opt", "state"), HasSubstr("a front of " + std::to_string(front.size()) + " points"));
  EXPECT_TRUE(doubles(loop.candidates()).empty()) << "evaluated in a copy: the graph rests";

  // Started again from its study (as after a kill): the same front, from the costs it recorded
  Loop again(8, "[gain 0 100]", "test/SlowProbe");
  for (const auto& [p, v] : {std::pair<std::string, std::string>{"objectives", "fitness_and_cost"},
                             {"algorithm", "random"},
                             {"budget", "30"},
                             {"study", study}})
    ASSERT_TRUE(again.g.setParameter("opt", p, v));
  again.g.start();
  ASSERT_TRUE(again.g.fireSlot("opt", "start"));
  ASSERT_TRUE(waitState(again.g, "finished")) << paramText(again.g, "opt", "state");
  EXPECT_EQ(frontOf(again.g), front);
  EXPECT_EQ(lines(study).size(), 32u) << "nothing evaluated again";
  std::remove(study.c_str());
}
