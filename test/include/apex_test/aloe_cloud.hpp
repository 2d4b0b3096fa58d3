// The real cloud the point-cloud node tests share: the Middlebury aloe pair's ground-truth disparity
// (opencv-doc's aloeGT.png) made into points, coloured from aloeL.jpg. Built once per process.
#pragma once

#include <gtest/gtest.h>
#include <pcl/common/io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "apex_nodes/cloud.hpp"
#include "apex_test/real_images.hpp"

namespace apex_test {

/** Every 8th pixel of aloe with a known disparity d (full size), at depth 160 / d metres through a
 *  camera of focal length 1000 px, coloured as aloeL.jpg: about 21,600 points, all finite. */
inline const pcl::PointCloud<pcl::PointXYZRGB>& aloe() {
  static const pcl::PointCloud<pcl::PointXYZRGB> points = [] {
    pcl::PointCloud<pcl::PointXYZRGB> out;
    const cv::Mat disparity = cv::imread(kOpenCvData + "/aloeGT.png", cv::IMREAD_GRAYSCALE);
    const cv::Mat colour = cv::imread(kOpenCvData + "/aloeL.jpg", cv::IMREAD_COLOR);
    EXPECT_FALSE(disparity.empty() || colour.empty()) << "opencv-doc's aloe pair (scripts/install_deps)";
    for (int v = 0; v < disparity.rows; v += 8)
      for (int u = 0; u < disparity.cols; u += 8) {
        const int d = disparity.at<std::uint8_t>(v, u);
        if (d == 0) continue;
        const cv::Vec3b bgr = colour.at<cv::Vec3b>(v, u);
        pcl::PointXYZRGB p(bgr[2], bgr[1], bgr[0]);
        p.z = 160.0f / d;
        p.x = (u - disparity.cols / 2.0f) * p.z / 1000.0f;
        p.y = (v - disparity.rows / 2.0f) * p.z / 1000.0f;
        out.push_back(p);
      }
    return out;
  }();
  return points;
}

/** aloe's x, y, z as a typed cloud of its own: what a direct PCL call on it takes. */
inline std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>> aloeXyz() {
  auto out = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::copyPointCloud(aloe(), *out);
  return out;
}

/** The header of the aloe cloud's messages: frame "camera", stamp 3.000000005. */
inline std_msgs::Header aloeHeader() {
  std_msgs::Header h;
  h.frame_id = "camera";
  h.stamp = ros::Time(3, 5);
  return h;
}

/** aloe as the cloud message a node receives, with aloeHeader(). */
inline std::shared_ptr<const apex_nodes::Cloud> aloeCloud() { return apex_nodes::makeCloud(aloeHeader(), aloe()); }

}  // namespace apex_test
