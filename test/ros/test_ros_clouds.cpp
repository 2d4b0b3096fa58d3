// A lidar's sensor_msgs/PointCloud2 (x, y, z, intensity) through the runtime, as a user's robot
// sends it: what PassThrough and VoxelGrid publish keeps the intensity of each point, every
// field, the frame and the stamp to the nanosecond.
#include <gmock/gmock.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_types.h>
#include <pcl_conversions/pcl_conversions.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>

#include <mutex>

namespace {

using Lidar = pcl::PointCloud<pcl::PointXYZI>;

/** 20 x 25 points, one metre away, intensity = index. */
Lidar lidarPoints() {
  Lidar points;
  for (int i = 0; i < 500; ++i) points.push_back(pcl::PointXYZI(0.01f * (i % 20), 0.01f * (i / 20), 1.f, float(i)));
  return points;
}

sensor_msgs::PointCloud2 lidarMessage() {
  sensor_msgs::PointCloud2 m;
  pcl::toROSMsg(lidarPoints(), m);
  m.header.frame_id = "velodyne";
  m.header.stamp = ros::Time(1700000000, 123456789);
  return m;
}

/** Sends the cloud every 50 ms until a message arrives on `topic` (the runtime may still be
 *  subscribing), or 30 s pass. */
sensor_msgs::PointCloud2ConstPtr sendAndReceive(const std::string& topic) {
  ros::NodeHandle nh;
  std::mutex m;
  sensor_msgs::PointCloud2ConstPtr got;
  auto sub = nh.subscribe<sensor_msgs::PointCloud2>(topic, 1, [&](const sensor_msgs::PointCloud2ConstPtr& msg) {
    std::lock_guard<std::mutex> l(m);
    got = msg;
  });
  auto pub = nh.advertise<sensor_msgs::PointCloud2>("/clouds/in", 1);
  const auto message = lidarMessage();
  for (auto deadline = ros::WallTime::now() + ros::WallDuration(30); ros::WallTime::now() < deadline;) {
    {
      std::lock_guard<std::mutex> l(m);
      if (got) return got;
    }
    pub.publish(message);
    ros::WallDuration(0.05).sleep();  // the pace of the resending, not a wait for a result
  }
  return nullptr;
}

std::vector<std::string> fieldNames(const sensor_msgs::PointCloud2& m) {
  std::vector<std::string> out;
  for (const auto& f : m.fields) out.push_back(f.name);
  return out;
}

TEST(Clouds, PassThroughKeepsEachPointsIntensityFrameAndStamp) {
  auto got = sendAndReceive("/clouds/near");
  ASSERT_TRUE(got) << "nothing on /clouds/near";
  EXPECT_EQ(got->header.frame_id, "velodyne");
  EXPECT_EQ(got->header.stamp, ros::Time(1700000000, 123456789));
  EXPECT_THAT(fieldNames(*got), ::testing::ElementsAre("x", "y", "z", "intensity"));
  Lidar near;
  pcl::fromROSMsg(*got, near);
  ASSERT_EQ(near.size(), 250u);  // x = 0.00 .. 0.09 of each row of 20
  for (std::size_t k = 0; k < near.size(); ++k) ASSERT_EQ(near[k].intensity, float((k / 10) * 20 + k % 10)) << k;
}

TEST(Clouds, VoxelGridAveragesIntensityAsPclDoes) {
  auto got = sendAndReceive("/clouds/voxels");
  ASSERT_TRUE(got) << "nothing on /clouds/voxels";
  EXPECT_EQ(got->header.stamp, ros::Time(1700000000, 123456789));
  pcl::VoxelGrid<pcl::PointXYZI> f;
  f.setInputCloud(std::make_shared<Lidar>(lidarPoints()));
  f.setLeafSize(0.05f, 0.05f, 0.05f);
  Lidar want, voxels;
  f.filter(want);
  pcl::fromROSMsg(*got, voxels);
  ASSERT_EQ(voxels.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(voxels[i].x, want[i].x) << i;
    ASSERT_EQ(voxels[i].intensity, want[i].intensity) << i;
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ros_clouds");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
