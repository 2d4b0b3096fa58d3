// LaserProjector against laser_geometry's LaserProjection called directly, field for field and byte
// for byte, on scans of a corridor made here (noise, NaN, no return, too near, too far), with each
// of its channels and a range cutoff; bad scans refused with their flaw. With a target_frame:
// transformLaserScanToPointCloud into the scan's own frame (tf2's identity, which needs no ROS), and
// a frame tf2 does not know as the node's error naming both frames. A transform that moves during
// the scan needs tf2 fed from /tf: test/ros/test_ros_tf.cpp has it.
#include <gmock/gmock.h>
#include <laser_geometry/laser_geometry.h>
#include <pcl_conversions/pcl_conversions.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2/buffer_core.h>

#include <cmath>
#include <limits>
#include <random>

#include "apex_nodes/types.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using ::testing::HasSubstr;
using Scan = sensor_msgs::LaserScan;
using Params = std::vector<std::pair<std::string, std::string>>;
namespace channel = laser_geometry::channel_option;

namespace {

/** A 270° scan, a reading every `step` degrees, from 0.4 m into a corridor 2.4 m wide that ends 8 m
 *  ahead; 5 mm of noise (seeded). Every 29th reading NaN, every 31st no return (+inf), every 43rd
 *  3 cm (below range_min), every 47th 25 m (above range_max); reading 100 exactly range_min, 200
 *  exactly range_max (laser_geometry keeps range_min <= r < cutoff). Intensities to match. */
Scan corridor(double step = 0.5) {
  Scan s;
  s.header.frame_id = "laser";
  s.header.stamp = ros::Time(3, 400);
  s.header.seq = 7;
  s.angle_min = float(-0.75 * M_PI);
  s.angle_increment = float(step * M_PI / 180);
  const int n = int(std::lround(270 / step)) + 1;
  s.angle_max = s.angle_min + (n - 1) * s.angle_increment;
  s.time_increment = 1.f / 57600, s.scan_time = 0.025f;
  s.range_min = 0.06f, s.range_max = 20.f;
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.005);
  for (int i = 0; i < n; ++i) {
    const double a = s.angle_min + i * double(s.angle_increment), c = std::cos(a), d = std::sin(a);
    const double to_end = c > 0 ? 8 / c : c < 0 ? -0.4 / c : 1e9, to_side = d != 0 ? 1.2 / std::abs(d) : 1e9;
    float r = float(std::min(to_end, to_side) + noise(random));
    if (i % 29 == 0) r = std::numeric_limits<float>::quiet_NaN();
    else if (i % 31 == 0) r = std::numeric_limits<float>::infinity();
    else if (i % 43 == 0) r = 0.03f;
    else if (i % 47 == 0) r = 25.f;
    else if (i == 100) r = s.range_min;
    else if (i == 200) r = s.range_max;
    s.ranges.push_back(r);
    s.intensities.push_back(float(500 + i % 300));
  }
  return s;
}

std::shared_ptr<const Scan> shared(Scan s) { return std::make_shared<const Scan>(std::move(s)); }

/** The points `m` holds against laser_geometry's cloud `direct`: header, layout, fields, bytes. */
void expectCloud(const Message& m, const sensor_msgs::PointCloud2& direct, const std::string& fields) {
  pcl::PCLPointCloud2 want;
  pcl_conversions::toPCL(direct, want);
  const auto got = m.as<apex_nodes::Cloud>();
  ASSERT_TRUE(got) << "expected a cloud, got " << m.typeName();
  EXPECT_EQ(got->header, direct.header);
  const pcl::PCLPointCloud2& p = *got->points;
  EXPECT_EQ(p.width, want.width);
  EXPECT_EQ(p.height, want.height);
  EXPECT_EQ(p.point_step, want.point_step);
  EXPECT_EQ(p.row_step, want.row_step);
  EXPECT_EQ(p.is_dense, want.is_dense);
  std::string names;
  ASSERT_EQ(p.fields.size(), want.fields.size());
  for (std::size_t f = 0; f < want.fields.size(); ++f) {
    EXPECT_EQ(p.fields[f].name, want.fields[f].name);
    EXPECT_EQ(p.fields[f].offset, want.fields[f].offset);
    EXPECT_EQ(p.fields[f].datatype, want.fields[f].datatype);
    EXPECT_EQ(p.fields[f].count, want.fields[f].count);
    names += (f ? " " : "") + p.fields[f].name;
  }
  EXPECT_EQ(names, fields);
  EXPECT_TRUE(p.data == want.data) << "the points' bytes differ";
}

/** The points `m` holds against laser_geometry's projection of `scan` (its header: the scan's). */
void expectProjected(const Message& m, const Scan& scan, double cutoff, int channels, const std::string& fields) {
  sensor_msgs::PointCloud2 direct;
  laser_geometry::LaserProjection().projectLaser(scan, direct, cutoff, channels);
  ASSERT_EQ(direct.header, scan.header);
  expectCloud(m, direct, fields);
}

Message project(const Scan& scan, const Params& params) {
  NodeHarness h("apex_nodes/LaserProjector", {"scan"}, "cloud", params);
  const Message m = h.run<Scan>(shared(scan));
  EXPECT_EQ(h.error(), "");
  return m;
}

TEST(LaserProjector, IsLaserGeometrysProjectionWithEachChannel) {
  const Scan scan = corridor();
  ASSERT_EQ(scan.ranges.size(), 541u);
  // laser_geometry's defaults: intensity and index, up to range_max
  const Message plain = project(scan, {});
  expectProjected(plain, scan, -1.0, channel::Default, "x y z intensity index");
  const std::uint32_t valid = plain.as<apex_nodes::Cloud>()->points->width;
  EXPECT_GT(valid, 400u);
  EXPECT_LT(valid, 541u);
  // every channel, cut at 3 m
  const Message all = project(scan, {{"range_cutoff", "3"}, {"distance", "true"}, {"timestamp", "true"}});
  expectProjected(all, scan, 3.0, channel::Intensity | channel::Index | channel::Distance | channel::Timestamp,
                  "x y z intensity index distances stamps");
  EXPECT_LT(all.as<apex_nodes::Cloud>()->points->width, valid);
  // none: x, y, z alone
  expectProjected(project(scan, {{"intensity", "false"}, {"index", "false"}}), scan, -1.0, channel::None, "x y z");
  // a scan without intensities has no intensity field, asked or not
  Scan bare = scan;
  bare.intensities.clear();
  expectProjected(project(bare, {}), bare, -1.0, channel::Default, "x y z index");
}

TEST(LaserProjector, ScansOfOtherAnglesThroughOneNodeAreEachProjectedAnew) {
  // laser_geometry keeps the sines and cosines of the last scan's angles: a scan of other angles
  // through the same node is projected with its own.
  NodeHarness h("apex_nodes/LaserProjector", {"scan"}, "cloud");
  for (const double step : {0.5, 0.25, 0.5, 1.0}) {
    const Scan scan = corridor(step);
    expectProjected(h.run<Scan>(shared(scan)), scan, -1.0, channel::Default, "x y z intensity index");
  }
  EXPECT_EQ(h.error(), "");
}

TEST(LaserProjector, AScanWithoutRangesOrWithMismatchedIntensitiesIsRefused) {
  NodeHarness h("apex_nodes/LaserProjector", {"scan"}, "cloud");
  Scan short_intensities = corridor();
  short_intensities.intensities.resize(3);
  EXPECT_TRUE(h.run<Scan>(shared(short_intensities)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("scan on frame 'laser' has 541 ranges but 3 intensities"));
  Scan empty = corridor();
  empty.ranges.clear(), empty.intensities.clear();
  EXPECT_TRUE(h.run<Scan>(shared(empty)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("received an empty scan on frame 'laser' (no ranges)"));
}

TEST(LaserProjector, IntoTheScansOwnFrameIsTransformLaserScanToPointCloudWithTf2sIdentity) {
  // tf2 maps a frame into itself with no transform given: the high-fidelity call runs here without
  // ROS, with its own handling of the channels (it adds index to time the readings, and drops it
  // again when not asked for).
  const Scan scan = corridor();
  const int channels = channel::Intensity | channel::Distance | channel::Timestamp;
  const Message got = project(scan, {{"target_frame", "laser"}, {"index", "false"}, {"distance", "true"}, {"timestamp", "true"}});
  tf2::BufferCore empty;
  sensor_msgs::PointCloud2 direct;
  laser_geometry::LaserProjection().transformLaserScanToPointCloud("laser", scan, direct, empty, -1.0, channels);
  EXPECT_EQ(direct.header.frame_id, "laser");
  EXPECT_GT(direct.width, 400u);
  expectCloud(got, direct, "x y z intensity distances stamps");
}

TEST(LaserProjector, ATargetFrameTf2DoesNotKnowIsAnErrorNamingBothFrames) {
  // no ROS here: the node's buffer stays empty, as a robot's before its first transform arrives
  NodeHarness h("apex_nodes/LaserProjector", {"scan"}, "cloud", {{"target_frame", "base_link"}});
  const Scan scan = corridor();
  EXPECT_TRUE(h.run<Scan>(shared(scan)).isNothing());
  // the scan's first and last reading (3 s 400 ns + 540 x 1/57600 s), then tf2's reason
  EXPECT_THAT(h.error(), HasSubstr("no transform laser -> base_link at 3.000000 (to 3.009375, the scan's last reading): "
                                   "\"base_link\" passed to lookupTransform argument target_frame does not exist"));
  // the node goes on: without a target frame the next scan is projected, and the error clears
  h.set("target_frame", "");
  expectProjected(h.run<Scan>(shared(scan)), scan, -1.0, channel::Default, "x y z intensity index");
  EXPECT_EQ(h.error(), "");
}

}  // namespace
