// What nodes that need a camera's geometry check of its model (sensor_msgs/CameraInfo), and a
// calibration file read into one.
#pragma once

#include <sensor_msgs/CameraInfo.h>

#include <string>

#include "apex_nodes/types.hpp"

namespace apex_nodes {

/** @brief Throws std::invalid_argument naming the camera (its frame) unless the model is
 *  calibrated (K not all zero) and, with an image, made for that image: the same size, and the
 *  same frame when both name one. */
void requireCameraFor(const sensor_msgs::CameraInfo& info, const Image* image = nullptr);

/** @brief A calibration file as a camera model: camera_calibration_parsers' YAML or INI (what
 *  ROS's camera_calibration writes), or OpenCV's calibration output (camera_matrix,
 *  distortion_coefficients, image_width, image_height; R = I, P = [K | 0] unless given).
 *  Throws std::invalid_argument naming the file and what is wrong. */
sensor_msgs::CameraInfo readCameraFile(const std::string& path);

}  // namespace apex_nodes
