// Writes the table demo's bag: an RGB-D camera (registered depth and colour, 320x240, with its
// camera_info) looking down at a table with three boxes on it that slide a little from frame to
// frame, the floor below; plus the ground truth (each box's centre and size in the camera's
// optical frame). Ray-cast, with 1 mm of depth noise; deterministic for the same options.
//   apex_make_table_bag OUT.bag TRUTH.yaml [--frames N] [--seed N]
#include <cv_bridge/cv_bridge.h>
#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "cli.hpp"

namespace {

constexpr int kWidth = 320, kHeight = 240;
constexpr double kFx = 262.5, kFy = 262.5, kCx = 159.5, kCy = 119.5;
constexpr const char* kFrame = "camera_color_optical_frame";

/** An axis-aligned box in the world (z up, the table top at z = 0) and its colour. */
struct Box {
  Eigen::Vector3d min, max;
  cv::Vec3b bgr;
};

/** The camera: 1 m behind the table's centre, 0.6 m above it, looking at it. Columns: the optical
 *  frame's x (right), y (down), z (forward) in the world; and its position. */
struct Camera {
  Eigen::Matrix3d axes;
  Eigen::Vector3d at{0, -1.0, 0.6};
  Camera() {
    const Eigen::Vector3d forward = (Eigen::Vector3d(0, 0, 0) - at).normalized();
    const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
    axes.col(0) = right, axes.col(1) = forward.cross(right), axes.col(2) = forward;
  }
  Eigen::Vector3d toCamera(const Eigen::Vector3d& world) const { return axes.transpose() * (world - at); }
};

/** The distance along `dir` from `from` to the box, if the ray hits it (slab test). */
double hit(const Box& b, const Eigen::Vector3d& from, const Eigen::Vector3d& dir) {
  double near = 0, far = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (std::abs(dir[i]) < 1e-12) {
      if (from[i] < b.min[i] || from[i] > b.max[i]) return far;
      continue;
    }
    double t0 = (b.min[i] - from[i]) / dir[i], t1 = (b.max[i] - from[i]) / dir[i];
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0), far = std::min(far, t1);
    if (near > far) return std::numeric_limits<double>::infinity();
  }
  return near;
}

/** The scene of frame `f`: the table (a thin slab), the floor, and three boxes sliding in x. */
std::vector<Box> scene(int f) {
  std::vector<Box> s;
  s.push_back({{-0.6, -0.4, -0.03}, {0.6, 0.4, 0.0}, {60, 90, 140}});  // the table's top (wood)
  s.push_back({{-3, -3, -0.78}, {3, 3, -0.75}, {120, 120, 120}});  // the floor
  const double sizes[3][3] = {{0.12, 0.10, 0.15}, {0.08, 0.16, 0.10}, {0.10, 0.10, 0.22}};
  const double y[3] = {-0.15, 0.05, 0.2}, x0[3] = {-0.3, 0.05, 0.35};
  const cv::Vec3b colours[3] = {{40, 40, 200}, {40, 170, 40}, {190, 90, 30}};
  for (int i = 0; i < 3; ++i) {
    const double x = x0[i] + 0.08 * std::sin(0.15 * f + 2.0 * i);
    s.push_back({{x - sizes[i][0] / 2, y[i] - sizes[i][1] / 2, 0.0},
                 {x + sizes[i][0] / 2, y[i] + sizes[i][1] / 2, sizes[i][2]},
                 colours[i]});
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> paths;
  int frames = 40;
  std::uint64_t seed = 20261126;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--frames" && i + 1 < argc) frames = static_cast<int>(apex_tools::number(arg, argv[++i], 1, 100000));
      else if (arg == "--seed" && i + 1 < argc) seed = apex_tools::number(arg, argv[++i], 0, ~std::uint64_t(0));
      else if (arg.rfind("--", 0) == 0) throw std::invalid_argument("unknown option '" + arg + "'");
      else paths.push_back(arg);
    }
    if (paths.size() != 2) throw std::invalid_argument("needs OUT.bag and TRUTH.yaml");
  } catch (const std::invalid_argument& e) {
    std::cerr << "apex_make_table_bag: " << e.what()
              << "\nusage: apex_make_table_bag OUT.bag TRUTH.yaml [--frames N] [--seed N]\n";
    return 2;
  }
  rosbag::Bag bag;
  try {
    bag.open(paths[0], rosbag::bagmode::Write);
  } catch (const rosbag::BagException& e) {
    std::cerr << "apex_make_table_bag: cannot write '" << paths[0] << "': " << e.what() << "\n";
    return 1;
  }
  sensor_msgs::CameraInfo info;
  info.width = kWidth, info.height = kHeight, info.distortion_model = "plumb_bob";
  info.D = {0, 0, 0, 0, 0};
  info.K = {kFx, 0, kCx, 0, kFy, kCy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {kFx, 0, kCx, 0, 0, kFy, kCy, 0, 0, 0, 1, 0};
  const Camera camera;
  cv::RNG rng(seed);
  std::ofstream truth(paths[1]);
  truth << "# ground truth of " << paths[0] << ": per frame, each box's centre and size in the frame '" << kFrame
        << "'\n# (x right, y down, z forward), metres\nboxes_per_frame: 3\nframes:\n";
  const ros::Time start(1700000000, 0);
  for (int f = 0; f < frames; ++f) {
    std_msgs::Header header;
    header.seq = f, header.stamp = start + ros::Duration(0.1 * f), header.frame_id = kFrame;
    const auto boxes = scene(f);
    cv::Mat depth(kHeight, kWidth, CV_16UC1, cv::Scalar(0)), colour(kHeight, kWidth, CV_8UC3, cv::Scalar(0, 0, 0));
    for (int v = 0; v < kHeight; ++v)
      for (int u = 0; u < kWidth; ++u) {
        const Eigen::Vector3d ray = camera.axes * Eigen::Vector3d((u - kCx) / kFx, (v - kCy) / kFy, 1.0);  // z_c = 1
        double best = std::numeric_limits<double>::infinity();
        const Box* seen = nullptr;
        for (const auto& b : boxes)
          if (double t = hit(b, camera.at, ray); t < best) best = t, seen = &b;
        if (!seen || best > 8.0) continue;  // beyond the sensor's range: no depth (0)
        const double z = best + rng.gaussian(0.001);
        depth.at<std::uint16_t>(v, u) = static_cast<std::uint16_t>(std::lround(z * 1000));
        colour.at<cv::Vec3b>(v, u) = seen->bgr;
      }
    info.header = header;
    bag.write("/camera/depth/image_raw", header.stamp, cv_bridge::CvImage(header, "16UC1", depth).toImageMsg());
    bag.write("/camera/color/image_raw", header.stamp, cv_bridge::CvImage(header, "bgr8", colour).toImageMsg());
    bag.write("/camera/color/camera_info", header.stamp, info);
    truth << "  - boxes:\n";
    for (std::size_t i = 2; i < boxes.size(); ++i) {
      const Eigen::Vector3d c = camera.toCamera((boxes[i].min + boxes[i].max) / 2), size = boxes[i].max - boxes[i].min;
      truth << "      - {centre: [" << c.x() << ", " << c.y() << ", " << c.z() << "], size: [" << size.x() << ", " << size.y()
            << ", " << size.z() << "]}\n";
    }
  }
  bag.close();
  std::cout << "apex_make_table_bag: " << frames << " frames in " << paths[0] << "\n";
  return 0;
}
