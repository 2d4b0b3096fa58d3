// The Optimizer's racing alone, ROS-free: its two rules (apex_nodes/generic/racing.hpp). The
// whole loop: test_tuning_workers.
#include <gmock/gmock.h>

#include <cmath>
#include <vector>

#include "racing.hpp"

using namespace apex_nodes::tuning;

namespace {

TEST(TQuantile, MatchesTheTablesValues) {
  EXPECT_NEAR(tQuantile(0.95, 4), 2.132, 0.02);
  EXPECT_NEAR(tQuantile(0.95, 9), 1.833, 0.01);
  EXPECT_NEAR(tQuantile(0.975, 20), 2.086, 0.01);
  EXPECT_NEAR(tQuantile(0.99, 30), 2.457, 0.01);
  EXPECT_NEAR(tQuantile(0.95, 100000), 1.645, 0.001);
  EXPECT_NEAR(tQuantile(0.5, 7), 0.0, 1e-9);
}

/** Feeds worker 0 the frame scores `scores` as means so far; the frame it was cut at (1-based),
 *  or 0 if it ran whole. */
int race(Racing& r, const std::vector<double>& scores, double needed, int rival) {
  double sum = 0;
  for (std::size_t i = 0; i < scores.size(); ++i) {
    sum += scores[i];
    if (r.frame(0, sum / (i + 1), needed, rival)) return static_cast<int>(i + 1);
  }
  return 0;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / v.size();
}

/** Twenty frames of a detector's F1, varied (mean 0.65): the rival's. */
const std::vector<double> kRival{0.6, 0.7, 0.5, 0.8, 0.6, 0.7, 0.8, 0.5, 0.6, 0.7,
                                 0.8, 0.6, 0.5, 0.7, 0.6, 0.8, 0.7, 0.6, 0.5, 0.7};

TEST(Racing, PairedCutsAClearlyWorsePassEarlyAndCountsItsEstimate) {
  Racing r;
  r.start(true, RacingRule::kPaired, 0.95, 1.0, false, 1);
  EXPECT_EQ(race(r, kRival, -HUGE_VAL, -1), 0) << "the first pass runs whole";
  EXPECT_DOUBLE_EQ(r.ended(0, 7, mean(kRival)), mean(kRival));
  std::vector<double> worse;  // 0.1 below the rival on every frame, give or take 0.02
  for (std::size_t i = 0; i < kRival.size(); ++i) worse.push_back(kRival[i] - 0.1 + (i % 2 ? 0.02 : -0.02));
  const int at = race(r, worse, mean(kRival), 7);
  EXPECT_EQ(at, Racing::kMinPairedFrames) << "clearly worse from its first frames (the bound would wait)";
  const double counted = r.ended(0, 8, 0);
  EXPECT_LT(counted, mean(kRival)) << "it loses where it competes";
  EXPECT_NEAR(counted, mean(worse), 0.01) << "counted as its estimate, not the bound";
  EXPECT_EQ(r.cuts(), 1);
  EXPECT_NEAR(r.framesShare(), (20.0 + at) / 40, 1e-9);
  EXPECT_EQ(r.summary(),
            "racing paired: 1 cut short, " + std::to_string(std::lround(100 * (20.0 + at) / 40)) + "% of the frames scored");
}

TEST(Racing, PairedLetsAPassAsGoodAsItsRivalRunWhole) {
  Racing r;
  r.start(true, RacingRule::kPaired, 0.95, 1.0, false, 1);
  race(r, kRival, -HUGE_VAL, -1);
  r.ended(0, 0, mean(kRival));
  std::vector<double> mixed;  // worse on half the frames, better on the others: as good
  for (std::size_t i = 0; i < kRival.size(); ++i) mixed.push_back(kRival[i] + (i % 2 ? 0.15 : -0.15));
  EXPECT_EQ(race(r, mixed, mean(kRival), 0), 0);
  EXPECT_DOUBLE_EQ(r.ended(0, 1, mean(mixed)), mean(mixed));
}

TEST(Racing, PairedWithoutTheRivalsFramesFallsBackOnTheBound) {
  // the bound: (0 * n + 1 * (20 - n)) / 20 < 0.7 from n = 7; paired with the rival's frames: at 5
  for (int rival : {0, -1, 42}) {  // kept; none; one whose frames were not kept (a remote worker's)
    Racing r;
    r.start(true, RacingRule::kPaired, 0.95, 1.0, false, 1);
    race(r, kRival, -HUGE_VAL, -1);
    r.ended(0, 0, mean(kRival));
    const std::vector<double> zeros(20, 0.0);
    EXPECT_EQ(race(r, zeros, 0.7, rival), rival == 0 ? 5 : 7) << rival;
    if (rival != 0) EXPECT_NEAR(r.ended(0, 1, 0), 13.0 / 20, 1e-9) << "counted as the bound";
  }
}

TEST(Racing, TheBoundRuleCutsOnlyWhatCannotCount) {
  Racing r;
  r.start(true, RacingRule::kBound, 0.95, 1.0, false, 1);
  race(r, kRival, -HUGE_VAL, -1);
  r.ended(0, 0, mean(kRival));
  std::vector<double> worse;
  for (double v : kRival) worse.push_back(v - 0.3);
  const int at = race(r, worse, mean(kRival), 0);  // the paired rule would cut at 5
  double sum = 0;
  int expected = 0;
  for (int n = 1; n <= 20 && !expected; ++n)
    if (sum += worse[n - 1], (sum + (20 - n)) / 20 < mean(kRival)) expected = n;
  EXPECT_EQ(at, expected);
  EXPECT_GT(at, Racing::kMinPairedFrames);
}

TEST(Racing, MinimizingCutsWhatIsClearlyLarger) {
  Racing r;
  r.start(true, RacingRule::kPaired, 0.95, 0.0, true, 1);  // errors: 0 at best
  const std::vector<double> errors{1, 2, 1.5, 1, 2, 1, 1.5, 2, 1, 1, 1, 2, 1.5, 1, 2, 1, 1.5, 2, 1, 1};
  race(r, errors, -HUGE_VAL, -1);
  r.ended(0, 0, mean(errors));
  std::vector<double> larger;
  for (double e : errors) larger.push_back(e + 3);
  EXPECT_EQ(race(r, larger, -mean(errors), 0), Racing::kMinPairedFrames) << "the bound would wait for 7";
  EXPECT_NEAR(r.ended(0, 1, 0), mean(larger), 0.01) << "told in the node's own sense: an error";
}

}  // namespace
