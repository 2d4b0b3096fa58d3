#include "apex_nodes/camera_model.hpp"

#include <camera_calibration_parsers/parse.h>

#include <algorithm>
#include <fstream>
#include <opencv2/core/persistence.hpp>
#include <stdexcept>

namespace apex_nodes {
namespace {

std::string cameraName(const sensor_msgs::CameraInfo& info) {
  return "camera model " + std::to_string(info.width) + "x" + std::to_string(info.height) + " on frame '" + info.header.frame_id +
         "'";
}

/** OpenCV's calibration output (calibration.cpp sample, cv::FileStorage); false if it is not one. */
bool readOpenCvFile(const std::string& path, sensor_msgs::CameraInfo& info) try {
  cv::FileStorage fs;
  if (!fs.open(path, cv::FileStorage::READ)) return false;
  cv::Mat K, D, R, P;
  fs["camera_matrix"] >> K;
  fs["distortion_coefficients"] >> D;
  if (K.rows != 3 || K.cols != 3 || fs["image_width"].empty() || fs["image_height"].empty()) return false;
  fs["rectification_matrix"] >> R;
  fs["projection_matrix"] >> P;
  info.width = static_cast<std::uint32_t>(static_cast<int>(fs["image_width"]));
  info.height = static_cast<std::uint32_t>(static_cast<int>(fs["image_height"]));
  K.convertTo(K, CV_64F);
  std::copy(K.begin<double>(), K.end<double>(), info.K.begin());
  if (!D.empty()) {
    D.convertTo(D, CV_64F);
    info.D.assign(D.begin<double>(), D.end<double>());
  }
  info.distortion_model = info.D.size() > 5 ? "rational_polynomial" : "plumb_bob";
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  if (R.rows == 3 && R.cols == 3) R.convertTo(R, CV_64F), std::copy(R.begin<double>(), R.end<double>(), info.R.begin());
  if (P.rows == 3 && P.cols == 4) {
    P.convertTo(P, CV_64F);
    std::copy(P.begin<double>(), P.end<double>(), info.P.begin());
  } else {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) info.P[r * 4 + c] = info.K[r * 3 + c];
  }
  return true;
} catch (const cv::Exception&) {  // not OpenCV's format (e.g. ROS's YAML, whose matrices are plain maps)
  return false;
}

}  // namespace

void requireCameraFor(const sensor_msgs::CameraInfo& info, const Image* image) {
  if (std::all_of(info.K.begin(), info.K.end(), [](double k) { return k == 0; }))
    throw std::invalid_argument(cameraName(info) + " is not calibrated: K is all zero");
  if (!image) return;
  const int w = image->mat.cols, h = image->mat.rows;
  if (int(info.width) != w || int(info.height) != h)
    throw std::invalid_argument(cameraName(info) + " is not for an image of " + std::to_string(w) + "x" + std::to_string(h));
  if (!info.header.frame_id.empty() && !image->header.frame_id.empty() && info.header.frame_id != image->header.frame_id)
    throw std::invalid_argument(cameraName(info) + " is not for the image on frame '" + image->header.frame_id + "'");
}

sensor_msgs::CameraInfo readCameraFile(const std::string& path) {
  if (path.empty()) throw std::invalid_argument("no calibration file: set 'file'");
  if (!std::ifstream(path)) throw std::invalid_argument("cannot read the calibration file '" + path + "'");
  sensor_msgs::CameraInfo info;
  std::string name;
  if (!readOpenCvFile(path, info) && !camera_calibration_parsers::readCalibration(path, name, info))
    throw std::invalid_argument("'" + path +
                                "' is neither a ROS camera calibration (YAML or INI) nor OpenCV's "
                                "(camera_matrix, distortion_coefficients, image_width, image_height)");
  requireCameraFor(info);
  return info;
}

}  // namespace apex_nodes
