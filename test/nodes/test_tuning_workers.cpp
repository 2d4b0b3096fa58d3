// The Optimizer's workers (copies of the evaluated part beside the graph) and racing (cutting a
// candidate's pass once it cannot count), on the loop of tuning_loop.hpp: each study row's fitness
// is its candidate's gain exactly when the candidate was in effect for every frame of its pass.
#include <gmock/gmock.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "tuning_loop.hpp"

using namespace apex_test;
using namespace apex_test::tuning;
using ::testing::HasSubstr;

namespace {

/** A run of `workers` written to a study: its rows after the two header lines. */
std::vector<std::string> studyOfRun(const std::string& algorithm, int workers, Loop& loop) {
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
bool scoredItsOwnValue(const std::string& row) {
  const auto a = row.find(','), b = row.find(',', a + 1);
  const double fitness = std::stod(row.substr(a + 1, b - a - 1)), gain = std::stod(row.substr(b + 1));
  return std::abs(fitness - gain) <= 1e-12 * std::max(1.0, gain);  // the mean of 20 equal numbers, rounded
}

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
    EXPECT_THAT(paramText(raced.g, "opt", "state"), HasSubstr("(" + std::to_string(cut) + " cut short)"));
    if (workers == 1) EXPECT_LT(raced.seen()->size(), whole.seen()->size() * 0.9) << "fewer frames scored";
  }
}

TEST(Optimizer, RacingWithABoundScoresBeatTurnsItselfOffAndTheRunIsTheSame) {
  Loop whole(20), raced(20);
  link(raced.g, "mean", "running", "opt", "running");
  link(raced.g, "opt", "cut", "seq", "end_pass");
  ASSERT_TRUE(raced.g.setParameter("opt", "racing", "true"));  // frame_score_bound 1: the gains reach 100
  const auto expected = studyOfRun("random", 1, whole);
  EXPECT_EQ(studyOfRun("random", 1, raced), expected);
  EXPECT_THAT(paramText(raced.g, "opt", "state"), HasSubstr("(0 cut short)"));
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
