// LaserRangeFilter, LaserAngleFilter and LaserMedianFilter on a scan of a room (a 2D lidar inside
// a rectangle, with noise, readings with no return, NaN and too near ones), each against the same
// computation written here, reading by reading; the header kept; bad scans refused with their flaw.
#include <gmock/gmock.h>
#include <sensor_msgs/LaserScan.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "apex_nodes/types.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using ::testing::HasSubstr;
using Scan = sensor_msgs::LaserScan;

namespace {

const float kInf = std::numeric_limits<float>::infinity();
const float kNan = std::numeric_limits<float>::quiet_NaN();

/** 720 readings all round from a lidar at (1, 0.5) in an 8 x 5 m room centred on the origin, 1 cm
 *  of noise (seeded); every 37th reading no return (+inf), every 53rd NaN, every 61st a 4 cm
 *  echo, every 71st 45 m (past range_max); intensities to match. */
Scan roomScan() {
  Scan s;
  s.header.frame_id = "laser";
  s.header.stamp = ros::Time(7, 250);
  s.header.seq = 12;
  s.angle_min = -M_PI;
  s.angle_increment = 2 * M_PI / 720;
  s.angle_max = s.angle_min + 719 * s.angle_increment;
  s.time_increment = 1e-4f, s.scan_time = 0.1f;
  s.range_min = 0.1f, s.range_max = 30.f;
  std::mt19937 random(53);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int i = 0; i < 720; ++i) {
    const double a = s.angle_min + i * double(s.angle_increment), c = std::cos(a), d = std::sin(a);
    const double to_x = c > 0 ? (4 - 1) / c : c < 0 ? (-4 - 1) / c : 1e9;  // to the walls x = +-4, y = +-2.5
    const double to_y = d > 0 ? (2.5 - 0.5) / d : d < 0 ? (-2.5 - 0.5) / d : 1e9;
    float r = static_cast<float>(std::min(to_x, to_y) + noise(random));
    if (i % 37 == 0) r = kInf;
    else if (i % 53 == 0) r = kNan;
    else if (i % 61 == 0) r = 0.04f;
    else if (i % 71 == 0) r = 45.f;
    s.ranges.push_back(r);
    s.intensities.push_back(static_cast<float>(100 + (7 * i) % 50));
  }
  return s;
}

std::shared_ptr<const Scan> shared(Scan s) { return std::make_shared<const Scan>(std::move(s)); }

/** The scan a node sent, its header the input's. */
Scan sent(const Message& m, const Scan& in) {
  auto s = m.as<Scan>();
  if (!s) throw std::runtime_error("expected a scan, got " + m.typeName());
  EXPECT_EQ(s->header, in.header);
  return *s;
}

/** Equal floats, or both NaN, element by element. */
void expectSame(const std::vector<float>& got, const std::vector<float>& want, const char* what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < want.size(); ++i)
    ASSERT_TRUE(got[i] == want[i] || (std::isnan(got[i]) && std::isnan(want[i])))
        << what << " " << i << ": " << got[i] << " vs " << want[i];
}

/** The scan's ranges with those below `lower` made `below`, above `upper` made `above`. */
std::vector<float> replaced(const Scan& s, double lower, double upper, float below, float above) {
  std::vector<float> out = s.ranges;
  for (float& r : out) {
    if (r < lower) r = below;
    else if (r > upper) r = above;
  }
  return out;
}

TEST(LaserFilters, LaserRangeFilterReplacesWhatLiesOutsideTheLimits) {
  NodeHarness h("apex_nodes/LaserRangeFilter", {"scan"}, "scan");
  const Scan in = roomScan();
  const std::size_t outside = std::count_if(in.ranges.begin(), in.ranges.end(), [](float r) { return r < 0.2 || r > 4.0; });
  ASSERT_GT(outside, 50u);  // walls beyond 4 m, the near echoes, the infinities
  h.set("limits", "[0.2, 4.0]");
  struct Case {
    const char* option;
    float below, above;
  };
  for (const Case& c : {Case{"nan", kNan, kNan}, Case{"inf", -kInf, kInf}, Case{"lower_and_upper", 0.2f, 4.0f}}) {
    h.set("replace_with", c.option);
    const Scan out = sent(h.run(shared(in)), in);
    expectSame(out.ranges, replaced(in, 0.2, 4.0, c.below, c.above), c.option);
    expectSame(out.intensities, in.intensities, "intensities");
    EXPECT_EQ(out.angle_min, in.angle_min);
    EXPECT_EQ(out.angle_increment, in.angle_increment);
  }
  h.set("use_message_range_limits", "true");  // the scan's own 0.1 .. 30 m
  const Scan out = sent(h.run(shared(in)), in);
  expectSame(out.ranges, replaced(in, in.range_min, in.range_max, in.range_min, in.range_max), "message limits");
  EXPECT_THAT(h.graph().setParameter("node", "limits", "[4, 1]").message(), HasSubstr("low 4 is above high 1"));
}

TEST(LaserFilters, LaserAngleFilterCutsTheScanToTheWindow) {
  NodeHarness h("apex_nodes/LaserAngleFilter", {"scan"}, "scan");
  h.set("angles", "[-1.0, 0.5]");
  const Scan in = roomScan();
  std::size_t first = in.ranges.size(), last = 0;
  for (std::size_t i = 0; i < in.ranges.size(); ++i) {
    const double a = in.angle_min + i * double(in.angle_increment);
    if (a >= -1.0 && a <= 0.5) first = std::min(first, i), last = i;
  }
  ASSERT_GT(last, first + 100);
  const Scan out = sent(h.run(shared(in)), in);
  expectSame(out.ranges, {in.ranges.begin() + first, in.ranges.begin() + last + 1}, "ranges");
  expectSame(out.intensities, {in.intensities.begin() + first, in.intensities.begin() + last + 1}, "intensities");
  EXPECT_EQ(out.angle_min, float(in.angle_min + first * double(in.angle_increment)));
  EXPECT_EQ(out.angle_max, float(in.angle_min + last * double(in.angle_increment)));
  EXPECT_GE(out.angle_min, -1.0f);
  EXPECT_LE(out.angle_max, 0.5f);
  EXPECT_EQ(out.angle_increment, in.angle_increment);
  EXPECT_EQ(out.range_max, in.range_max);
  h.set("angles", "[4.0, 5.0]");  // behind the scan's end at +pi
  EXPECT_TRUE(h.run(shared(in)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("none of its readings"));
  EXPECT_THAT(h.graph().setParameter("node", "angles", "[1, -1]").message(), HasSubstr("low 1 is above high -1"));
}

/** Each value the median of the non-NaN ones within `half` places (nth_element at the middle). */
std::vector<float> medians(const std::vector<float>& in, int half) {
  std::vector<float> out;
  for (int i = 0; i < int(in.size()); ++i) {
    std::vector<float> window;
    for (int j = std::max(0, i - half); j <= std::min(int(in.size()) - 1, i + half); ++j)
      if (!std::isnan(in[j])) window.push_back(in[j]);
    if (window.empty()) {
      out.push_back(kNan);
      continue;
    }
    std::nth_element(window.begin(), window.begin() + window.size() / 2, window.end());
    out.push_back(window[window.size() / 2]);
  }
  return out;
}

TEST(LaserFilters, LaserMedianFilterTakesEachWindowsMedian) {
  NodeHarness h("apex_nodes/LaserMedianFilter", {"scan"}, "scan");
  const Scan in = roomScan();
  for (int window : {5, 1, 9}) {
    h.set("window", std::to_string(window));
    const Scan out = sent(h.run(shared(in)), in);
    expectSame(out.ranges, medians(in.ranges, window / 2), "ranges");
    expectSame(out.intensities, medians(in.intensities, window / 2), "intensities");
  }
  const Scan out = sent(h.run(shared(in)), in);  // window 9: the lone NaN, near and far readings gone
  EXPECT_TRUE(std::none_of(out.ranges.begin(), out.ranges.end(), [](float r) { return std::isnan(r) || r < 0.1 || r > 30; }));
  EXPECT_THAT(h.graph().setParameter("node", "window", "4").message(), HasSubstr("not on the step"));
}

TEST(LaserFilters, BadScansAreRefusedNamingTheFlaw) {
  for (const char* type : {"apex_nodes/LaserRangeFilter", "apex_nodes/LaserAngleFilter", "apex_nodes/LaserMedianFilter"}) {
    SCOPED_TRACE(type);
    NodeHarness h(type, {"scan"}, "scan");
    Scan empty = roomScan();
    empty.ranges.clear(), empty.intensities.clear();
    EXPECT_TRUE(h.run(shared(empty)).isNothing());
    EXPECT_THAT(h.error(), HasSubstr("received an empty scan on frame 'laser' (no ranges)"));
    Scan uneven = roomScan();
    uneven.intensities.pop_back();
    EXPECT_TRUE(h.run(shared(uneven)).isNothing());
    EXPECT_THAT(h.error(), HasSubstr("scan on frame 'laser' has 720 ranges but 719 intensities"));
    Scan bare = roomScan();  // no intensities at all is a scan like any other
    bare.intensities.clear();
    const auto out = h.run(shared(bare)).as<Scan>();
    ASSERT_TRUE(out) << h.error();
    EXPECT_EQ(out->ranges.size(), 720u);
    EXPECT_TRUE(out->intensities.empty());
  }
  NodeHarness h("apex_nodes/LaserRangeFilter", {"scan"}, "scan");
  h.set("use_message_range_limits", "true");
  Scan inverted = roomScan();
  inverted.range_min = 40.f;
  EXPECT_TRUE(h.run(shared(inverted)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("has range_min 40.000000 above range_max 30.000000"));
}

}  // namespace
