// Writes the demo's bag: camera frames of dark number signs on textured
// backgrounds, seen by a camera mounted on its side (as in the paper's SICK
// Robot Day setup), and a point cloud per frame; plus the ground truth.
//   apex_make_demo_bag OUT.bag TRUTH.yaml [frames]
// Deterministic: the same files every time.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl_conversions/pcl_conversions.h>
#include <cv_bridge/cv_bridge.h>
#include <rosbag/bag.h>

#include <fstream>
#include <iostream>
#include <opencv2/imgproc.hpp>

namespace {

constexpr int kWidth = 640, kHeight = 480;  // the scene upright; the camera sees it turned

cv::Mat background(cv::RNG& rng) {
  cv::Mat bg(kHeight, kWidth, CV_8UC3);
  const int base = rng.uniform(150, 200);
  for (int y = 0; y < kHeight; ++y)  // a soft gradient ...
    bg.row(y).setTo(cv::Scalar(base + y / 12, base + y / 16, base + y / 10));
  cv::Mat noise(bg.size(), CV_8UC3);
  rng.fill(noise, cv::RNG::UNIFORM, -18, 18);  // ... some grain ...
  cv::add(bg, noise, bg, cv::noArray(), CV_8UC3);
  for (int i = 0; i < 12; ++i) {  // ... and a few light scratches
    const cv::Point a(rng.uniform(0, kWidth), rng.uniform(0, kHeight)), b(rng.uniform(0, kWidth), rng.uniform(0, kHeight));
    cv::line(bg, a, b, cv::Scalar::all(rng.uniform(200, 250)), 1, cv::LINE_AA);
  }
  return bg;
}

/** Up to `count` non-overlapping sign boxes, kept apart by a margin. */
std::vector<cv::Rect> placeSigns(cv::RNG& rng, int count) {
  std::vector<cv::Rect> boxes;
  for (int tries = 0; tries < 400 && static_cast<int>(boxes.size()) < count; ++tries) {
    const int w = rng.uniform(60, 110), h = rng.uniform(60, 110);
    const cv::Rect box(rng.uniform(20, kWidth - w - 20), rng.uniform(20, kHeight - h - 20), w, h);
    const cv::Rect grown(box.x - 25, box.y - 25, box.width + 50, box.height + 50);
    bool free = true;
    for (const auto& b : boxes) free &= (b & grown).empty();
    if (free) boxes.push_back(box);
  }
  return boxes;
}

void drawSign(cv::Mat& img, const cv::Rect& box, int number, cv::RNG& rng) {
  cv::rectangle(img, box, cv::Scalar::all(rng.uniform(15, 45)), cv::FILLED);
  const std::string text = std::to_string(number);
  const double scale = box.height / 45.0;
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 3, &baseline);
  const cv::Point at(box.x + (box.width - size.width) / 2, box.y + (box.height + size.height) / 2);
  cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar::all(235), 3, cv::LINE_AA);
}

/** A floor plane, two boxes standing on it, and far clutter beyond 3 m. */
sensor_msgs::PointCloud2 cloud(cv::RNG& rng, const std_msgs::Header& header) {
  pcl::PointCloud<pcl::PointXYZ> c;
  for (int i = 0; i < 12000; ++i)
    c.push_back(pcl::PointXYZ(rng.uniform(-2.f, 2.f), 0.8f + rng.gaussian(0.005), rng.uniform(0.3f, 5.f)));
  for (int b = 0; b < 2; ++b)
    for (int i = 0; i < 3000; ++i)
      c.push_back(pcl::PointXYZ(-0.8f + 1.2f * b + rng.uniform(0.f, 0.4f), rng.uniform(0.4f, 0.8f), 1.5f + rng.uniform(0.f, 0.4f)));
  sensor_msgs::PointCloud2 msg;
  pcl::toROSMsg(c, msg);
  msg.header = header;
  return msg;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: apex_make_demo_bag OUT.bag TRUTH.yaml [frames]\n";
    return 2;
  }
  const int frames = argc > 3 ? std::atoi(argv[3]) : 40;
  cv::RNG rng(20261121);
  rosbag::Bag bag;
  try {
    bag.open(argv[1], rosbag::bagmode::Write);
  } catch (const rosbag::BagException& e) {
    std::cerr << "apex_make_demo_bag: cannot write '" << argv[1] << "': " << e.what() << "\n";
    return 1;
  }
  std::ofstream truth(argv[2]);
  truth << "# ground truth of " << argv[1] << ": per image frame, the signs in the upright scene\n"
        << "image_topic: /camera/image_raw\ncloud_topic: /camera/points\nframes:\n";
  const ros::Time start(1700000000, 0);
  for (int f = 0; f < frames; ++f) {
    std_msgs::Header header;
    header.seq = f;
    header.stamp = start + ros::Duration(0.1 * f);
    header.frame_id = "camera";
    cv::Mat scene = background(rng);
    const auto boxes = placeSigns(rng, 1 + f % 4);
    truth << "  - {stamp: " << header.stamp.toNSec() << ", signs: " << boxes.size() << ", boxes: [";
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      drawSign(scene, boxes[i], rng.uniform(0, 10), rng);
      const auto& b = boxes[i];
      truth << (i ? ", " : "") << "[" << b.x << ", " << b.y << ", " << b.width << ", " << b.height << "]";
    }
    truth << "]}\n";
    cv::Mat seen;
    cv::rotate(scene, seen, cv::ROTATE_90_CLOCKWISE);  // the camera lies on its side
    bag.write("/camera/image_raw", header.stamp, cv_bridge::CvImage(header, "bgr8", seen).toImageMsg());
    std_msgs::Header cloud_header = header;
    cloud_header.stamp += ros::Duration(0.005);  // the depth sensor, 5 ms later: one frame in a 20 ms sync window
    bag.write("/camera/points", cloud_header.stamp, cloud(rng, cloud_header));
  }
  bag.close();
  std::cout << "wrote " << frames << " frames to " << argv[1] << " and the ground truth to " << argv[2] << "\n";
  return truth ? 0 : 1;
}
