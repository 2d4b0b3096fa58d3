// The Optimizer's searches in ask/tell form (apex_nodes/search.hpp). Their quality against
// scipy is checked by test/optimizer/compare_scipy.py.
#include <gmock/gmock.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "apex_nodes/search.hpp"

using namespace apex_nodes::search;
using ::testing::HasSubstr;

namespace {

/** The search of the algorithm named `name`, as the Optimizer makes it for its `algorithm` choice. */
std::unique_ptr<Search> make(const std::string& name, std::vector<Dimension> dims, Settings s = {}) {
  const auto& table = algorithms();
  const auto it = std::find_if(table.begin(), table.end(), [&](const auto& o) { return name == o.name; });
  EXPECT_TRUE(it != table.end()) << "no algorithm '" << name << "'";
  if (it == table.end()) return nullptr;
  auto made = makeSearch(it->value, std::move(dims), s);
  EXPECT_TRUE(made) << made.message();
  return made ? std::move(made).value() : nullptr;
}

std::vector<std::vector<double>> run(Search& s, const std::function<double(const std::vector<double>&)>& fitness) {
  std::vector<std::vector<double>> asked;
  while (!s.done()) {
    asked.push_back(s.ask());
    s.tell(fitness(asked.back()));
  }
  return asked;
}

double minusSphere(const std::vector<double>& x) {
  double s = 0;
  for (double v : x) s += v * v;
  return -s;
}

TEST(Search, TheSameSeedGivesTheSameCandidates) {
  Settings s;
  s.budget = 60, s.seed = 7;
  const std::vector<Dimension> box{{"a", -1, 1}, {"b", 0, 10, true}};
  for (const char* algorithm : {"differential_evolution", "random"}) {
    auto one = run(*make(algorithm, box, s), minusSphere);
    auto two = run(*make(algorithm, box, s), minusSphere);
    EXPECT_EQ(one, two) << algorithm;
    s.seed = 8;
    EXPECT_NE(run(*make(algorithm, box, s), minusSphere), one) << algorithm;
    s.seed = 7;
  }
}

TEST(Search, CandidatesStayInTheirRangesAndIntegersAreWhole) {
  Settings s;
  s.budget = 300;
  for (const char* algorithm : {"differential_evolution", "random", "grid"}) {
    auto search = make(algorithm, {{"k", 1, 31, true}, {"c", -2.5, 2.5}}, s);
    for (const auto& x : run(*search, [](const std::vector<double>& x) { return x[0] - std::abs(x[1]); })) {
      EXPECT_GE(x[0], 1) << algorithm;
      EXPECT_LE(x[0], 31) << algorithm;
      EXPECT_EQ(x[0], std::round(x[0])) << algorithm;
      EXPECT_GE(x[1], -2.5) << algorithm;
      EXPECT_LE(x[1], 2.5) << algorithm;
    }
    EXPECT_EQ(search->evaluations(), 300);
  }
}

TEST(Search, AGridWalksEveryPointOnceIncludingTheCorners) {
  Settings s;
  s.budget = 9;
  auto asked = run(*make("grid", {{"a", 0, 1}, {"b", 10, 20}}, s), minusSphere);
  std::set<std::vector<double>> points(asked.begin(), asked.end());
  EXPECT_EQ(points.size(), 9u);
  EXPECT_TRUE(points.count({0, 10}));
  EXPECT_TRUE(points.count({1, 20}));
  EXPECT_TRUE(points.count({0.5, 15}));
}

TEST(Search, DifferentialEvolutionKeepsTheBestAndImprovesOnItsStart) {
  Settings s;
  s.budget = 1500, s.population = 30;
  auto search = make("differential_evolution", {{"x", -5, 5}, {"y", -5, 5}, {"z", -5, 5}}, s);
  double start_best = -HUGE_VAL;
  int n = 0;
  while (!search->done()) {
    const double f = minusSphere(search->ask());
    search->tell(f);
    if (++n <= 30) start_best = std::max(start_best, f);
    EXPECT_GE(search->bestFitness(), f);
  }
  EXPECT_GT(search->bestFitness(), start_best);
  EXPECT_GT(search->bestFitness(), -1e-3);
  EXPECT_EQ(minusSphere(search->best()), search->bestFitness());
}

TEST(Search, AFailedEvaluationCountsAsTheWorst) {
  auto search = make("random", {{"x", 0, 1}});
  search->ask();
  search->tell(0.5);
  search->ask();
  search->tell(std::nan(""));
  EXPECT_EQ(search->bestFitness(), 0.5);
}

TEST(Search, ImmediateDifferentialEvolutionWaitsForEachFitness) {
  auto search = make("differential_evolution", {{"x", 0, 1}});
  EXPECT_THROW(search->tell(1), std::logic_error);
  search->ask();
  EXPECT_FALSE(search->canAsk());
  EXPECT_THROW(search->ask(), std::logic_error);
}

TEST(Search, ManyCandidatesOutAtOnceToldInAnyOrderGiveTheSameRun) {
  Settings s;
  s.budget = 50, s.seed = 3, s.population = 10, s.deferred = true;
  const std::vector<Dimension> box{{"a", -1, 1}, {"b", 0, 10, true}};
  for (const char* algorithm : {"differential_evolution", "random", "grid"}) {
    auto serial = make(algorithm, box, s);
    const auto expected = run(*serial, minusSphere);
    auto batched = make(algorithm, box, s);
    std::vector<std::vector<double>> asked;
    std::size_t most_out = 0;
    while (!batched->done()) {
      std::vector<int> out;
      while (batched->canAsk()) {
        out.push_back(batched->asked());
        asked.push_back(batched->ask());
      }
      most_out = std::max(most_out, out.size());
      for (auto it = out.rbegin(); it != out.rend(); ++it) batched->tell(*it, minusSphere(asked[*it]));  // last first
    }
    EXPECT_EQ(asked, expected) << algorithm;
    EXPECT_EQ(batched->best(), serial->best()) << algorithm;
    EXPECT_EQ(most_out, std::string(algorithm) == "differential_evolution" ? 10u : 50u)
        << algorithm << ": a generation, or everything";
  }
  auto search = make("random", {{"x", 0, 1}});
  search->ask();
  EXPECT_THROW(search->tell(3, 1.0), std::logic_error) << "a candidate not out";
}

TEST(Search, ThresholdsNameTheirRivalForRacing) {
  Settings s;
  s.budget = 60, s.seed = 3, s.population = 5;
  for (bool deferred : {false, true}) {
    SCOPED_TRACE(deferred ? "deferred" : "immediate");
    s.deferred = deferred;
    auto de = make("differential_evolution", {{"a", -1, 1}, {"b", -1, 1}}, s);
    std::map<int, double> told;  // evaluation -> fitness
    while (!de->done()) {
      std::vector<std::pair<int, std::vector<double>>> out;
      while (de->canAsk()) {
        const int id = de->asked();
        out.emplace_back(id, de->ask());
      }
      for (const auto& [id, x] : out) {
        const int rival = de->rival(id);
        if (id < 5) {
          EXPECT_EQ(rival, -1) << "a first population's member has nothing to beat";
        } else {
          ASSERT_TRUE(told.count(rival)) << id << " competes with " << rival << ", not yet scored";
          EXPECT_EQ(de->threshold(id), told.at(rival)) << id;
          EXPECT_EQ((rival < 5 ? rival : rival - 5) % 5, (id - 5) % 5) << "the member its trial is for";
        }
      }
      for (const auto& [id, x] : out) de->tell(id, told[id] = minusSphere(x));
    }
  }
  auto random = make("random", {{"a", -1, 1}}, s);
  EXPECT_EQ(random->rival(random->asked()), -1);
  std::map<int, double> told;
  for (int id = 0; id < 10; ++id) {
    const auto x = random->ask();
    if (id > 0) EXPECT_EQ(random->threshold(id), told.at(random->rival(id))) << "the best so far";
    random->tell(told[id] = minusSphere(x));
  }
}

TEST(Search, BadSettingsAreRefusedWithTheReason) {
  Settings s;
  EXPECT_THAT(makeSearch(Algorithm::kRandom, {}, s).message(), HasSubstr("no dimensions"));
  EXPECT_THAT(makeSearch(Algorithm::kRandom, {{"x", 2, 1}}, s).message(), HasSubstr("dimension 'x'"));
  EXPECT_THAT(makeSearch(Algorithm::kGrid, {{"k", 0.2, 0.8, true}}, s).message(), HasSubstr("integer but its range holds none"));
  s.population = 3;
  EXPECT_THAT(makeSearch(Algorithm::kDifferentialEvolution, {{"x", 0, 1}}, s).message(), HasSubstr("population 3 is below 4"));
  s.population = 0, s.CR = 1.5;
  EXPECT_THAT(makeSearch(Algorithm::kDifferentialEvolution, {{"x", 0, 1}}, s).message(), HasSubstr("CR"));
  s.CR = 0.9, s.budget = 0;
  EXPECT_THAT(makeSearch(Algorithm::kRandom, {{"x", 0, 1}}, s).message(), HasSubstr("budget 0"));
}

TEST(Search, TheAlgorithmsKeepTheNamesSavedGraphsUse) {
  std::vector<std::string> names;
  for (const auto& o : algorithms()) names.push_back(o.name);
  EXPECT_EQ(names, (std::vector<std::string>{"differential_evolution", "random", "grid"}));
}

}  // namespace
