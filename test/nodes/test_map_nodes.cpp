// CloudToOccupancyGrid and HeightMap against the same binning written here, cell by cell: on the
// aloe cloud (opencv-doc's aloe pair's ground truth made into points; a band of its depth z seen
// along z) and on a room made here (floor, walls, a box, a lamp above the band, points outside the
// grid, NaN), over the band's points or a fixed area. Cells on the edges of a float resolution
// fall as the message's own numbers place them.
#include <gmock/gmock.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "apex_nodes/cloud.hpp"
#include "apex_nodes/maps.hpp"
#include "apex_test/aloe_cloud.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using ::testing::HasSubstr;
using Points = pcl::PointCloud<pcl::PointXYZ>;
using Params = std::vector<std::pair<std::string, std::string>>;

namespace {

const float kNan = std::numeric_limits<float>::quiet_NaN();

/** A grid and, per cell (row by row from the origin), the count and the highest z of the band's points in it. */
struct Binning {
  double x0 = 0, y0 = 0;
  float resolution = 0;
  int width = 0, height = 0;
  std::vector<int> counts;
  std::vector<float> top;
};

/** The finite points with z in [low, high]. */
Points band(const Points& in, double low, double high) {
  Points out;
  for (const auto& p : in)
    if (std::isfinite(p.x) && std::isfinite(p.y) && p.z >= low && p.z <= high) out.push_back(p);
  return out;
}

/** `points` binned on the grid of `b` (its geometry set). */
Binning binned(Binning b, const Points& points) {
  b.counts.assign(std::size_t(b.width) * b.height, 0);
  b.top.assign(b.counts.size(), kNan);
  for (const auto& p : points) {
    const double i = std::floor((p.x - b.x0) / b.resolution), j = std::floor((p.y - b.y0) / b.resolution);
    if (i < 0 || i >= b.width || j < 0 || j >= b.height) continue;
    const std::size_t k = std::size_t(j) * b.width + std::size_t(i);
    ++b.counts[k];
    if (std::isnan(b.top[k]) || p.z > b.top[k]) b.top[k] = p.z;
  }
  return b;
}

/** The grid just covering `points`: its origin their least x and y. */
Binning covering(const Points& points, double resolution) {
  Binning b;
  b.resolution = float(resolution);
  double x1 = points[0].x, y1 = points[0].y, x2 = x1, y2 = y1;
  for (const auto& p : points)
    x1 = std::min<double>(x1, p.x), y1 = std::min<double>(y1, p.y), x2 = std::max<double>(x2, p.x),
    y2 = std::max<double>(y2, p.y);
  b.x0 = x1, b.y0 = y1;
  b.width = int(std::floor((x2 - x1) / b.resolution)) + 1;
  b.height = int(std::floor((y2 - y1) / b.resolution)) + 1;
  return binned(b, points);
}

Binning fixedGrid(double x0, double y0, int width, int height, double resolution, const Points& points) {
  Binning b;
  b.x0 = x0, b.y0 = y0, b.width = width, b.height = height, b.resolution = float(resolution);
  return binned(b, points);
}

void expectInfo(const nav_msgs::MapMetaData& info, const Binning& want, const std_msgs::Header& header) {
  EXPECT_EQ(info.map_load_time, header.stamp);
  EXPECT_EQ(info.resolution, want.resolution);
  EXPECT_EQ(int(info.width), want.width);
  EXPECT_EQ(int(info.height), want.height);
  EXPECT_EQ(info.origin.position.x, want.x0);
  EXPECT_EQ(info.origin.position.y, want.y0);
  EXPECT_EQ(info.origin.position.z, 0.0);
  EXPECT_EQ(info.origin.orientation.w, 1.0);
}

/** CloudToOccupancyGrid's grid against `want`: 100 with min_points or more, 0 with fewer, -1 with none. */
void expectGrid(const Message& m, const Binning& want, const std_msgs::Header& header, int min_points) {
  const auto grid = m.as<nav_msgs::OccupancyGrid>();
  ASSERT_TRUE(grid) << "expected a grid, got " << m.typeName();
  EXPECT_EQ(grid->header, header);
  expectInfo(grid->info, want, header);
  ASSERT_EQ(grid->data.size(), want.counts.size());
  int kinds[3] = {0, 0, 0};
  for (std::size_t k = 0; k < want.counts.size(); ++k) {
    const int n = want.counts[k], expected = n == 0 ? -1 : n >= min_points ? 100 : 0;
    ASSERT_EQ(int(grid->data[k]), expected) << "cell " << k % want.width << ", " << k / want.width << ": " << n << " points";
    ++kinds[expected == -1 ? 0 : expected == 0 ? 1 : 2];
  }
  EXPECT_GT(kinds[0], 0) << "no unknown cell";
  EXPECT_GT(kinds[1], 0) << "no free cell";
  EXPECT_GT(kinds[2], 0) << "no occupied cell";
}

/** HeightMap's image and grid against `want`: each cell's highest z, NaN where none fell. */
void expectHeights(const std::shared_ptr<const apex_nodes::Cloud>& cloud, const Params& grid_params, const Binning& want) {
  Params params;  // the grid's, without CloudToOccupancyGrid's min_points
  for (const auto& p : grid_params)
    if (p.first != "min_points") params.push_back(p);
  NodeHarness h("apex_nodes/HeightMap", {"cloud"}, "heights", params);
  const Message m = h.run<apex_nodes::Cloud>(cloud);
  const auto image = m.as<apex_nodes::Image>();
  ASSERT_TRUE(image) << h.error();
  EXPECT_EQ(image->header, cloud->header);
  EXPECT_EQ(image->encoding, "32FC1");
  ASSERT_EQ(image->mat.size(), cv::Size(want.width, want.height));
  ASSERT_EQ(image->mat.type(), CV_32FC1);
  for (int j = 0; j < want.height; ++j)
    for (int i = 0; i < want.width; ++i) {
      const float got = image->mat.at<float>(j, i), top = want.top[std::size_t(j) * want.width + i];
      ASSERT_TRUE(got == top || (std::isnan(got) && std::isnan(top)))
          << "cell " << i << ", " << j << ": " << got << " vs " << top;
    }
  NodeHarness g("apex_nodes/HeightMap", {"cloud"}, "info", params);
  const auto info = g.run<apex_nodes::Cloud>(cloud).as<nav_msgs::MapMetaData>();
  ASSERT_TRUE(info) << g.error();
  expectInfo(*info, want, cloud->header);
}

/** A 4 x 3 m room around the origin, 2 m high, in frame "map": a floor (z = 0) every 7 cm, walls at
 *  x = +-2 every 5 cm, a 40 x 50 x 60 cm box at x = 0.5, y = -0.3 every 4 cm, a lamp at z = 2.5, and
 *  points outside: far away, NaN, a NaN height. */
Points room() {
  Points out;
  for (double x = -2; x <= 2; x += 0.07)
    for (double y = -1.5; y <= 1.5; y += 0.07) out.push_back({float(x), float(y), 0.f});
  for (double y = -1.5; y <= 1.5; y += 0.05)
    for (double z = 0.05; z <= 2; z += 0.05) out.push_back({-2.f, float(y), float(z)}), out.push_back({2.f, float(y), float(z)});
  for (double x = 0.5; x <= 0.9; x += 0.04)
    for (double y = -0.3; y <= 0.2; y += 0.04) out.push_back({float(x), float(y), 0.6f});
  for (double z = 0.1; z <= 0.6; z += 0.1) out.push_back({0.5f, -0.3f, float(z)});  // the box's edge: a stack in one cell
  out.push_back({0.f, 0.f, 2.5f});
  out.push_back({7.f, 1.f, 1.f});
  out.push_back({kNan, kNan, kNan});
  out.push_back({1.f, 1.f, kNan});
  return out;
}

std_msgs::Header roomHeader() {
  std_msgs::Header h;
  h.frame_id = "map";
  h.stamp = ros::Time(5, 9);
  return h;
}

TEST(MapNodes, TheAloeCloudsBandIsBinnedCellByCell) {
  const Points aloe = *aloeXyz();
  const Params params{{"z_band", "[1.8, 2.6]"}, {"resolution", "0.05"}, {"min_points", "4"}};
  NodeHarness h("apex_nodes/CloudToOccupancyGrid", {"cloud"}, "grid", params);
  const Binning want = covering(band(aloe, 1.8, 2.6), 0.05);  // about 64 x 47 cells, 671 with points
  expectGrid(h.run<apex_nodes::Cloud>(aloeCloud()), want, aloeHeader(), 4);
  expectHeights(aloeCloud(), params, want);
}

TEST(MapNodes, ARoomOnAFixedGridAndOverItsPoints) {
  const Points points = room();
  const auto cloud = apex_nodes::makeCloud(roomHeader(), points);
  // A fixed grid of 10 cm cells from (-2.5, -2): the floor below the band, the lamp above it and the
  // far point outside are left out.
  const Params fixed{{"z_band", "[0.1, 2.0]"}, {"resolution", "0.1"}, {"extent", "fixed"}, {"origin", "[-2.5, -2.0]"},
                     {"width", "50"},          {"height", "40"},      {"min_points", "3"}};
  NodeHarness h("apex_nodes/CloudToOccupancyGrid", {"cloud"}, "grid", fixed);
  const Binning want = fixedGrid(-2.5, -2.0, 50, 40, 0.1, band(points, 0.1, 2.0));
  expectGrid(h.run<apex_nodes::Cloud>(cloud), want, roomHeader(), 3);
  expectHeights(cloud, fixed, want);
  // Over the band's points (the floor in it now, and the far point), 5 cm cells.
  const Params over{{"z_band", "[-1.0, 2.2]"}, {"resolution", "0.05"}, {"min_points", "4"}};
  NodeHarness h2("apex_nodes/CloudToOccupancyGrid", {"cloud"}, "grid", over);
  const Binning all = covering(band(points, -1.0, 2.2), 0.05);
  EXPECT_EQ(all.x0, -2.0);
  EXPECT_EQ(all.y0, -1.5);
  expectGrid(h2.run<apex_nodes::Cloud>(cloud), all, roomHeader(), 4);
  expectHeights(cloud, over, all);
}

TEST(CloudToOccupancyGrid, AGridOverNoPointOrTooManyCellsIsAnError) {
  NodeHarness h("apex_nodes/CloudToOccupancyGrid", {"cloud"}, "grid");
  h.set("z_band", "[10.0, 20.0]");
  const auto cloud = apex_nodes::makeCloud(roomHeader(), room());
  EXPECT_TRUE(h.run<apex_nodes::Cloud>(cloud).isNothing());
  EXPECT_THAT(h.error(),
              HasSubstr("none of the cloud's " + std::to_string(room().size()) + " points is within z [10.000000, 20.000000]"));
  Points far;
  far.push_back({-50.f, -50.f, 1.f}), far.push_back({50.f, 50.f, 1.f});
  h.set("z_band", "[0.0, 2.0]");
  h.set("resolution", "0.001");
  EXPECT_TRUE(h.run<apex_nodes::Cloud>(apex_nodes::makeCloud(roomHeader(), far)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("over 100000000 cells"));
  // A fixed grid takes the same cloud: its two points fall outside.
  h.set("extent", "fixed");
  const Message m = h.run<apex_nodes::Cloud>(apex_nodes::makeCloud(roomHeader(), far));
  ASSERT_TRUE(m.as<nav_msgs::OccupancyGrid>()) << h.error();
  const auto& data = m.as<nav_msgs::OccupancyGrid>()->data;
  EXPECT_EQ(data.size(), 400u * 400u);
  EXPECT_TRUE(std::all_of(data.begin(), data.end(), [](std::int8_t v) { return v == -1; }));
}

}  // namespace
