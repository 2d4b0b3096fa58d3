// Bags for the bag node tests: frames of an image and, 5 ms later, a cloud, every
// 100 ms from t = 1000 s, and a text topic; written once per process under the temp directory.
#pragma once

#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/String.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace apex_test {

/** A directory of this test process's own under the temp directory, removed when the process
 *  ends normally (by that process alone: not by a child it forked). */
inline std::filesystem::path bagDirectory() {
  struct Owned {
    pid_t owner = getpid();
    std::filesystem::path dir = std::filesystem::temp_directory_path() / ("apex_bag_test_" + std::to_string(owner));
    ~Owned() {
      std::error_code ignored;
      if (getpid() == owner) std::filesystem::remove_all(dir, ignored);
    }
  };
  static const Owned owned;
  std::filesystem::create_directories(owned.dir);
  return owned.dir;
}

const ros::Time kBegin(1000, 0);
inline ros::Time frameTime(int k) { return kBegin + ros::Duration(0.1 * k); }

inline sensor_msgs::Image image(int k) {
  sensor_msgs::Image m;
  m.header.stamp = frameTime(k);
  m.height = 2, m.width = 3, m.encoding = "mono8", m.step = 3;
  m.data.assign(6, static_cast<std::uint8_t>(k % 256));
  return m;
}

inline sensor_msgs::PointCloud2 cloud(int k) {
  sensor_msgs::PointCloud2 m;
  m.header.stamp = frameTime(k);
  m.height = 1, m.width = 1, m.point_step = 12, m.row_step = 12, m.is_dense = true;
  for (int i = 0; i < 3; ++i) {
    sensor_msgs::PointField f;
    f.name = std::string(1, "xyz"[i]), f.offset = 4 * i, f.datatype = sensor_msgs::PointField::FLOAT32, f.count = 1;
    m.fields.push_back(f);
  }
  m.data.assign(12, 0);
  return m;
}

inline sensor_msgs::CameraInfo cameraInfo(int k) {
  sensor_msgs::CameraInfo m;
  m.header.stamp = frameTime(k);
  m.width = 3, m.height = 2, m.K = {100, 0, 1.5, 0, 100, 1, 0, 0, 1};
  return m;
}

/** A bag of `frames` frames: an image with its camera_info, then 5 ms later a cloud, every 100 ms;
 *  and a text topic. */
inline std::string writeBag(int frames) {
  const std::string path = (bagDirectory() / ("frames_v2_" + std::to_string(frames) + ".bag")).string();
  if (std::filesystem::exists(path)) return path;
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  std_msgs::String note;
  note.data = "not a frame";
  for (int k = 0; k < frames; ++k) {
    bag.write("/camera/image_raw", frameTime(k), image(k));
    bag.write("/camera/camera_info", frameTime(k), cameraInfo(k));
    bag.write("/camera/points", frameTime(k) + ros::Duration(0.005), cloud(k));
  }
  bag.write("/notes", frameTime(0), note);
  return path;
}

}  // namespace apex_test
