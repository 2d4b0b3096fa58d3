// Malformed messages from the network: each is refused with a message naming what is
// wrong, before any pixel or point is read (these crashed the runtime before: sizes
// whose 32-bit product wrapped around, clouds whose fields or steps did not add up).
#include <gmock/gmock.h>
#include <sensor_msgs/LaserScan.h>
#include <boost/make_shared.hpp>
#include <sensor_msgs/image_encodings.h>

#include "apex_nodes/cloud.hpp"
#include "apex_nodes/ros_convert.hpp"
#include "apex_test/node_harness.hpp"

using namespace apex_test;
using ::testing::HasSubstr;

namespace {

sensor_msgs::ImagePtr image(std::uint32_t width, std::uint32_t height, std::uint32_t step, std::size_t bytes,
                            const std::string& encoding = sensor_msgs::image_encodings::MONO8) {
  auto m = boost::make_shared<sensor_msgs::Image>();
  m->width = width, m->height = height, m->step = step, m->encoding = encoding;
  m->data.resize(bytes);
  return m;
}

/** An x, y, z float cloud of width x height points, `bytes` of data. */
sensor_msgs::PointCloud2Ptr cloud(std::uint32_t width, std::uint32_t height, std::size_t bytes) {
  auto m = boost::make_shared<sensor_msgs::PointCloud2>();
  m->width = width, m->height = height, m->point_step = 16, m->row_step = 16 * width;
  for (std::uint32_t i = 0; i < 3; ++i) {
    sensor_msgs::PointField f;
    f.name = std::string(1, char('x' + i)), f.offset = 4 * i, f.datatype = sensor_msgs::PointField::FLOAT32, f.count = 1;
    m->fields.push_back(f);
  }
  m->data.resize(bytes);
  return m;
}

std::string refusal(const sensor_msgs::ImageConstPtr& m) {
  try {
    apex_nodes::fromRos(m);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

std::string refusal(const sensor_msgs::PointCloud2ConstPtr& m) {
  try {
    apex_nodes::fromRos(m);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(BadMessages, ImagesWhoseSizesDoNotAddUpAreRefused) {
  EXPECT_EQ(refusal(image(4, 3, 4, 12)), "(accepted)");
  // height x step = 2^32 + 2^16 wraps to 2^16 in 32 bits: matched a 64 KiB buffer
  EXPECT_THAT(refusal(image(65536, 65536, 65537, 65536)), HasSubstr("step x height needs 4295032832"));
  EXPECT_THAT(refusal(image(1, 65537, 65536, 65536)), HasSubstr("over 65536 pixels"));
  EXPECT_THAT(refusal(image(4, 3, 4, 11)), HasSubstr("data has 11 bytes"));
  EXPECT_THAT(refusal(image(4, 3, 2, 12)), HasSubstr("shorter than a row"));
  EXPECT_THAT(refusal(image(0, 3, 4, 12)), HasSubstr("no pixels"));
  EXPECT_THAT(refusal(image(4, 3, 12, 36, "rgb-ish")), HasSubstr("unknown encoding"));
  EXPECT_THAT(refusal(image(4, 3, 12, 35, "bgr8")), HasSubstr("image 4x3 'bgr8' on frame '': data has 35 bytes"));
}

TEST(BadMessages, CloudsWhoseFieldsOrStepsDoNotAddUpAreRefused) {
  EXPECT_EQ(refusal(cloud(10, 1, 160)), "(accepted)");
  EXPECT_THAT(refusal(cloud(10000000, 1, 0)), HasSubstr("data has 0 bytes"));
  auto wrapped = cloud(65537, 65536, 16);  // 2^16 x (2^16 + 1) points in 16 bytes
  wrapped->row_step = 16;
  EXPECT_THAT(refusal(wrapped), HasSubstr("over 2^28 points"));
  auto short_rows = cloud(10, 1, 160);
  short_rows->row_step = 16;
  EXPECT_THAT(refusal(short_rows), HasSubstr("row_step 16 is shorter"));
  auto short_data = cloud(10, 1, 100);
  EXPECT_THAT(refusal(short_data), HasSubstr("data has 100 bytes"));
  auto far = cloud(10, 1, 160);
  far->fields[1].offset = 1u << 30;
  EXPECT_THAT(refusal(far), HasSubstr("field 'y' (offset 1073741824) does not fit"));
  auto no_step = cloud(10, 1, 160);
  no_step->point_step = 0;
  EXPECT_THAT(refusal(no_step), HasSubstr("point_step is 0"));
  auto odd = cloud(10, 1, 160);
  odd->fields[2].datatype = 9;
  EXPECT_THAT(refusal(odd), HasSubstr("field 'z' has the unknown datatype 9"));
  auto no_z = cloud(10, 1, 160);
  no_z->fields.pop_back();
  EXPECT_THAT(refusal(no_z), HasSubstr("has no field 'z' (its fields: x, y)"));
  EXPECT_THAT(refusal(cloud(65536, 65536, 0)), HasSubstr("over 2^28 points"));
}

TEST(BadMessages, ACloudWithoutPointsIsAnEmptyCloud) {
  // Found by fuzz_ros_messages: PCL's conversion indexed point 0 of a cloud of width 0 with data.
  auto empty = cloud(0, 1, 64);
  EXPECT_EQ(refusal(empty), "(accepted)");
  EXPECT_EQ(apex_nodes::pointCount(*apex_nodes::fromRos(empty)), 0u);
}

TEST(BadMessages, AScanWithMismatchedArraysIsANodeErrorAndTheNextOneFlows) {
  NodeHarness h("apex_nodes/LaserScanToCloud", {"scan"}, "cloud");
  auto scan = std::make_shared<sensor_msgs::LaserScan>();
  scan->header.frame_id = "lidar";
  scan->angle_increment = 0.1f;
  scan->range_min = 0.1f, scan->range_max = 10.f;
  scan->ranges = {1.f, 2.f, 3.f};
  scan->intensities = {1.f};
  EXPECT_TRUE(h.run(std::shared_ptr<const sensor_msgs::LaserScan>(scan)).isNothing());
  EXPECT_THAT(h.error(), HasSubstr("has 3 ranges but 1 intensities"));
  scan->intensities.clear();
  EXPECT_FALSE(h.run(std::shared_ptr<const sensor_msgs::LaserScan>(scan)).isNothing());
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
